#pragma once
// The Content-Security-Policy every HTTP reply carries. The page runs only its own script files:
// no inline <script>, no on* attributes, no eval, so markup that ever slipped into the page could
// not run. What else the page loads: its style sheet (no style attributes: inline style is set
// through element.style, which the policy allows), frames as blob: URLs and scan slices as data:
// URLs, the WebSocket and fetches to itself. Nothing may frame it, no plugin runs, and no <base>
// can redirect its relative URLs.
namespace orthosim::net {

inline constexpr const char* kContentSecurityPolicy =
    "default-src 'self'; script-src 'self'; style-src 'self'; img-src 'self' blob: data:; "
    "connect-src 'self' ws: wss:; object-src 'none'; base-uri 'none'; form-action 'self'; "
    "frame-ancestors 'none'";

}  // namespace orthosim::net
