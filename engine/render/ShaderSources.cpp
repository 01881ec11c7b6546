#include "render/ShaderSources.hpp"

namespace orthosim::render::shaders {

// Lighting per vertex (Gouraud): a skin triangle covers a few pixels at most, so per-pixel lighting
// would look the same and cost far more on a CPU rasteriser. Two lights fixed to the camera (key
// above left, fill right) light every view alike; both sides are lit for open bone pieces.
const char* const kSurfaceVertex = R"(#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec3 aRestPosition;
layout(location = 3) in vec3 aRestNormal;
layout(location = 4) in vec2 aUv;
layout(location = 5) in vec2 aScalar;  // value, 1 in the map / 0 without a value
uniform mat4 uModel;       // rigid pose (bone pieces); identity for the skin
uniform mat4 uView;
uniform mat4 uProjection;
uniform int uAtRest;       // 1: the rest surface (before)
uniform int uValueSource;  // 0 none, 1 displacement from rest, 2 aScalar
uniform float uSpecular;
out vec2 vUv;
out float vValue;
out float vInMap;
out vec2 vLight;           // diffuse + ambient factor of the front (x) and back (y) side
out vec2 vHighlight;       // specular of the front and back side
void main() {
  vec3 p = uAtRest == 1 ? aRestPosition : aPosition;
  vec3 n0 = uAtRest == 1 ? aRestNormal : aNormal;
  vec4 eye = uView * uModel * vec4(p, 1.0);
  vec3 n = normalize(mat3(uView * uModel) * n0);  // rigid maps only: no inverse transpose needed
  vec3 v = normalize(-eye.xyz);
  vec3 key = normalize(vec3(-0.4, 0.5, 1.0));
  vec3 fill = normalize(vec3(0.7, -0.1, 0.7));
  vec3 halfway = normalize(key + v);
  vLight = 0.2 + vec2(0.65 * max(dot(n, key), 0.0) + 0.25 * max(dot(n, fill), 0.0),
                      0.65 * max(dot(-n, key), 0.0) + 0.25 * max(dot(-n, fill), 0.0));
  vHighlight = uSpecular * vec2(pow(max(dot(n, halfway), 0.0), 24.0), pow(max(dot(-n, halfway), 0.0), 24.0));
  vUv = aUv;
  float displacement = uAtRest == 1 ? 0.0 : length(aPosition - aRestPosition);
  vValue = uValueSource == 1 ? displacement : aScalar.x;
  vInMap = uValueSource == 2 ? aScalar.y : 1.0;
  gl_Position = uProjection * eye;
}
)";

const char* const kSurfaceFragment = R"(#version 330 core
in vec2 vUv;
in float vValue;
in float vInMap;
in vec2 vLight;
in vec2 vHighlight;
uniform int uColorSource;  // 0 flat uColor, 1 texture, 2 vValue through the ramp
uniform vec4 uColor;       // flat colour; its alpha is the opacity for every source
uniform sampler2D uTexture;
uniform sampler2D uRamp;
uniform vec2 uRange;       // values at the ramp's two ends
uniform vec4 uNoValue;     // colour of a vertex without a value (kNoValueColor)
out vec4 fragColor;
void main() {
  vec3 base = uColor.rgb;
  if (uColorSource == 1) base = texture(uTexture, vUv).rgb;
  if (uColorSource == 2) {
    float t = clamp((vValue - uRange.x) / (uRange.y - uRange.x), 0.0, 1.0);
    float n = float(textureSize(uRamp, 0).x);  // texel centres: t = 0 and 1 hit the end colours
    base = texture(uRamp, vec2((t * (n - 1.0) + 0.5) / n, 0.5)).rgb;
    if (vInMap < 0.5) base = uNoValue.rgb;  // no value here (outside the region of interest)
  }
  float light = gl_FrontFacing ? vLight.x : vLight.y;
  float highlight = gl_FrontFacing ? vHighlight.x : vHighlight.y;
  fragColor = vec4(base * light + vec3(highlight), uColor.a);
}
)";

const char* const kOverlayVertex = R"(#version 330 core
layout(location = 0) in vec2 aPixel;
layout(location = 1) in vec4 aColor;
uniform vec2 uViewport;
out vec4 vColor;
void main() {
  gl_Position = vec4(2.0 * aPixel.x / uViewport.x - 1.0, 1.0 - 2.0 * aPixel.y / uViewport.y, 0.0, 1.0);
  vColor = aColor;
}
)";

const char* const kOverlayFragment = R"(#version 330 core
in vec4 vColor;
out vec4 fragColor;
void main() { fragColor = vColor; }
)";

}  // namespace orthosim::render::shaders
