// "New patient" from a CT or CBCT scan (docs/protocol.md, /api/scans): the scan's files are sent
// once and staged on the server; each change of a threshold or a seed asks for a new preview (the
// segmentation drawn over three slices) of the staged scan; "Import" makes the case and shows what
// the server read, built and suggested. Server text is always put in with textContent.
"use strict";

const scan = {
  token: null, series: "", preview: null, seeds: {}, busy: false, again: false, timer: null, ranged: false,
};

function scanStatus(text, kind = "info") {
  const line = document.createElement("div");
  line.className = kind;
  line.textContent = text;
  $("scan-status").replaceChildren(line);
}

function authHeaders(more = {}) {
  return token() ? { ...more, Authorization: `Bearer ${token()}` } : more;
}

function refusal(reply, fallback) {
  const text = (reply && reply.message) || fallback;
  return reply && reply.field ? `${text} (field ${reply.field})` : text;
}

async function scanRequest(path, body, method = "POST") {
  const response = await fetch(path, {
    method, headers: authHeaders({ "Content-Type": "application/json" }), body: JSON.stringify(body),
  });
  let reply = null;
  try { reply = await response.json(); } catch (e) { reply = { message: response.statusText }; }
  return { status: response.status, reply };
}

// ---- staging ------------------------------------------------------------------------------------
function stageScan() {
  const folder = $("scan-folder").files, zip = $("scan-zip").files;
  if (!folder.length && !zip.length) return scanStatus("choose the scan's folder or a .zip first", "error");
  const data = new FormData();
  if (zip.length) data.append("dicom_zip", zip[0], zip[0].name);
  else for (const f of folder) data.append("dicom", f, f.webkitRelativePath || f.name);
  if (scan.token) scanRequest(`/api/scans/${scan.token}`, {}, "DELETE");  // the one sent before
  resetScan();
  const xhr = new XMLHttpRequest();
  xhr.open("POST", "/api/scans");
  if (token()) xhr.setRequestHeader("Authorization", `Bearer ${token()}`);
  const progress = $("scan-progress");
  progress.hidden = false;
  progress.value = 0;
  $("stage-scan").disabled = true;
  scanStatus(`sending ${zip.length ? zip[0].name : `${folder.length} files`}…`);
  xhr.upload.onprogress = (e) => {
    if (!e.lengthComputable) return;
    progress.value = 0.9 * (e.loaded / e.total);
    if (e.loaded === e.total) scanStatus("reading the series…");
  };
  xhr.onerror = () => { $("stage-scan").disabled = false; scanStatus("the upload failed: is the server running?", "error"); };
  xhr.onload = () => {
    $("stage-scan").disabled = false;
    let reply = null;
    try { reply = JSON.parse(xhr.responseText); } catch (e) { reply = { message: xhr.statusText }; }
    if (xhr.status !== 201) {
      progress.value = 0;
      return scanStatus(`scan refused: ${refusal(reply, xhr.statusText)}`, "error");
    }
    progress.value = 1;
    scanStaged(reply);
  };
  xhr.send(data);
}

function resetScan() {
  scan.token = null;
  scan.series = "";
  scan.preview = null;
  scan.seeds = {};
  scan.ranged = false;
  $("scan-series-choice").hidden = true;
  $("scan-preview").hidden = true;
  $("scan-images").replaceChildren();
  $("scan-notes").replaceChildren();
  $("scan-report").replaceChildren();
}

function seriesLabel(s) {
  return `${s.description || "(no description)"}: ${s.modality || "no modality"}, ${s.files} files, ${s.columns} x ${s.rows}`;
}

function scanStaged(reply) {
  scan.token = reply.token;
  const select = $("scan-series");
  const options = [];
  if (reply.series.length > 1) {
    const none = document.createElement("option");
    none.value = "";
    none.textContent = `choose one of ${reply.series.length} series`;
    options.push(none);
  }
  for (const s of reply.series) {
    const o = document.createElement("option");
    o.value = s.uid;
    o.textContent = seriesLabel(s);
    options.push(o);
  }
  select.replaceChildren(...options);
  $("scan-series-choice").hidden = reply.series.length < 2;
  if (reply.series.length > 1) return scanStatus(`the scan holds ${reply.series.length} series: choose one`);
  scan.series = reply.series[0].uid;
  scanStatus(`read: ${reply.read}; segmenting…`);
  requestPreview();
}

// ---- preview ------------------------------------------------------------------------------------
function previewBody() {
  const body = {};
  if (scan.series) body.series = scan.series;
  if (scan.ranged) {
    body.skin_threshold = Number($("scan-skin").value);
    body.bone_threshold = Number($("scan-bone").value);
  }
  if (scan.seeds.mandible) body.mandible_seed = scan.seeds.mandible;
  if (scan.seeds.skull) body.skull_seed = scan.seeds.skull;
  return body;
}

// One preview at a time; a change during one asks again when it ends, with the latest values.
async function requestPreview() {
  if (!scan.token) return;
  if (scan.busy) { scan.again = true; return; }
  scan.busy = true;
  scan.again = false;
  $("scan-preview").dataset.state = "working";
  try {
    const { status, reply } = await scanRequest(`/api/scans/${scan.token}/preview`, previewBody());
    if (status === 200) showPreview(reply);
    else if (reply.error === "several_series") scanStatus("choose a series first", "error");
    else scanStatus(`segmentation refused: ${refusal(reply, "error")}`, "error");
    if (status === 404) resetScan();
  } catch (e) {
    scanStatus(`the preview failed: ${e.message}`, "error");
  } finally {
    scan.busy = false;
    $("scan-preview").dataset.state = "ready";
    if (scan.again) requestPreview();
  }
}

function previewSoon() {
  clearTimeout(scan.timer);
  scan.timer = setTimeout(requestPreview, 400);
}

function setRanges(reply) {
  // Around what the server chose: Hounsfield units for a CT, the histogram's scale for a CBCT.
  const skin = $("scan-skin"), bone = $("scan-bone");
  skin.min = Math.round(reply.skin_threshold - 800); skin.max = Math.round(reply.skin_threshold + 800);
  bone.min = Math.round(reply.bone_threshold - 1000); bone.max = Math.round(reply.bone_threshold + 1500);
  skin.value = reply.skin_threshold;
  bone.value = reply.bone_threshold;
  scan.ranged = true;
}

function showPreview(reply) {
  scan.preview = reply;
  if (!scan.ranged) setRanges(reply);
  $("scan-skin-value").textContent = `${Math.round(reply.skin_threshold)}`;
  $("scan-bone-value").textContent = `${Math.round(reply.bone_threshold)}`;
  $("scan-preview").hidden = false;
  const figures = reply.images.map((image, n) => {
    const figure = document.createElement("figure");
    const box = document.createElement("div");
    box.className = "scan-slice";
    const img = document.createElement("img");
    img.src = image.src;  // a data: URL of the server's PNG
    img.alt = `${image.plane} slice`;
    img.dataset.plane = image.plane;
    img.addEventListener("click", (e) => placeSeed(n, e));
    box.append(img);
    for (const kind of ["mandible", "skull"]) {
      const at = pixelOf(image, reply[`${kind}_seed`]);
      if (!at) continue;
      const dot = document.createElement("span");
      dot.className = `seed ${kind}`;
      dot.style.left = `${(100 * (at.u + 0.5)) / image.width}%`;
      dot.style.top = `${(100 * (at.v + 0.5)) / image.height}%`;
      dot.title = `${kind} seed`;
      box.append(dot);
    }
    const caption = document.createElement("figcaption");
    caption.textContent = `${image.plane}: ${image.placed}`;
    figure.append(box, caption);
    return figure;
  });
  $("scan-images").replaceChildren(...figures);
  const notes = [reply.read, ...reply.read_warnings, ...reply.notes].filter(Boolean).map((text) => {
    const li = document.createElement("li");
    li.textContent = text;
    return li;
  });
  $("scan-notes").replaceChildren(...notes);
  scanStatus(`segmented with skin ${Math.round(reply.skin_threshold)}, bone ${Math.round(reply.bone_threshold)} (${reply.threshold_source}): skull blue, mandible orange, air cyan, skin outline pink`);
}

const dot3 = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];

// The pixel a point (LPS mm) lies over in a slice, when it is within 10 mm of it.
function pixelOf(image, p) {
  if (!p) return null;
  const d = [p[0] - image.origin[0], p[1] - image.origin[1], p[2] - image.origin[2]];
  const u = dot3(d, image.column) / dot3(image.column, image.column);
  const v = dot3(d, image.row) / dot3(image.row, image.row);
  const off = [d[0] - u * image.column[0] - v * image.row[0], d[1] - u * image.column[1] - v * image.row[1],
    d[2] - u * image.column[2] - v * image.row[2]];
  if (Math.sqrt(dot3(off, off)) > 10 || u < 0 || v < 0 || u >= image.width || v >= image.height) return null;
  return { u, v };
}

function placeSeed(n, event) {
  const image = scan.preview.images[n];
  const rect = event.target.getBoundingClientRect();
  const u = ((event.clientX - rect.left) / rect.width) * image.width - 0.5;
  const v = ((event.clientY - rect.top) / rect.height) * image.height - 0.5;
  const p = [0, 1, 2].map((k) => image.origin[k] + u * image.column[k] + v * image.row[k]);
  const kind = document.querySelector('input[name="scan-seed"]:checked').value;
  scan.seeds[kind] = p.map((x) => Math.round(x * 10) / 10);
  scanStatus(`${kind} seed at (${scan.seeds[kind].join(", ")}) mm; segmenting…`);
  requestPreview();
}

// ---- import -------------------------------------------------------------------------------------
async function importScan() {
  if (!scan.token) return scanStatus("send a scan first", "error");
  const id = $("scan-id").value.trim();
  if (!id) return scanStatus("give the case an id", "error");
  const body = {
    ...previewBody(), id, name: $("scan-name").value, oral_cavity: $("scan-oral").value,
    cuts: [...document.querySelectorAll('#scan-cuts input[name="scan-cut"]:checked')].map((c) => c.value),
  };
  const started = Date.now();
  const working = $("scan-working");
  let stage = "starting";
  const tick = () => {
    working.textContent = `${stage}… ${Math.round((Date.now() - started) / 1000)} s`;
  };
  // The import's stage, asked for beside it (GET answers at once).
  const poll = async () => {
    try {
      const response = await fetch(`/api/scans/${scan.token}`, { headers: authHeaders({}) });
      if (response.ok) {
        const now = await response.json();
        if (typeof now.stage === "string" && now.stage) stage = now.stage;
      }
    } catch (e) { /* the import's own reply says what went wrong */ }
    tick();
  };
  tick();
  const ticker = setInterval(poll, 700);
  working.hidden = false;
  $("import-scan").disabled = true;
  scanStatus("importing: this takes a minute for a full scan");
  say(`importing scan as patient ${id}…`);
  try {
    const { status, reply } = await scanRequest(`/api/scans/${scan.token}/import`, body);
    if (status !== 201) {
      scanStatus(`not imported: ${refusal(reply, "error")}`, "error");
      return say(`import refused: ${refusal(reply, "error")}`, "error");
    }
    resetScan();
    showScanReport(reply);
    scanStatus(`imported ${reply.case.name} (${reply.case.id}); opening it`);
    say(`patient ${reply.case.id} imported from a scan; opening it`);
    state.openAfterList = reply.case.id;
    send({ type: "list_cases" });
  } catch (e) {
    scanStatus(`the import failed: ${e.message}`, "error");
  } finally {
    clearInterval(ticker);
    working.hidden = true;
    $("import-scan").disabled = false;
  }
}

function showScanReport(reply) {
  const parts = [];
  const section = (title, lines) => {
    if (!lines || !lines.length) return;
    const h = document.createElement("div");
    h.textContent = title;
    const ul = document.createElement("ul");
    for (const text of lines) {
      const li = document.createElement("li");
      li.textContent = text;
      ul.append(li);
    }
    parts.push(h, ul);
  };
  section("Scan:", reply.scan);
  section("Suggested landmarks, to confirm or move:", reply.suggested);
  section("Built:", reply.built);
  section("Warnings:", reply.warnings);
  const frame = document.createElement("div");
  frame.textContent = `Frame: ${reply.frame}`;
  parts.push(frame);
  $("scan-report").replaceChildren(...parts);
}

// The osteotomy choices as the surfaces form has them.
function copyCutChoice() {
  const copy = $("cut-choice").cloneNode(true);
  copy.id = "scan-cut-choice";
  for (const box of copy.querySelectorAll('input[name="cut"]')) {
    box.name = "scan-cut";
    box.setAttribute("aria-label", `scan cut ${box.value}`);
  }
  $("scan-cuts").replaceChildren(copy);
}

copyCutChoice();
$("stage-scan").addEventListener("click", stageScan);
$("scan-series").addEventListener("change", () => {
  scan.series = $("scan-series").value;
  scan.ranged = false;  // another series: the server's thresholds again
  scan.seeds = {};
  if (scan.series) { scanStatus("reading the series and segmenting…"); requestPreview(); }
});
for (const id of ["scan-skin", "scan-bone"])
  $(id).addEventListener("input", () => {
    $(`${id}-value`).textContent = $(id).value;
    previewSoon();
  });
$("scan-auto-seeds").addEventListener("click", () => { scan.seeds = {}; requestPreview(); });
$("import-scan").addEventListener("click", importScan);
