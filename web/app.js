// The planning page: talks to orthosim serve over /ws (docs/protocol.md) and shows the streamed
// frames. While a slider moves, the poses go out every SEND_INTERVAL_MS at most: the server draws
// each at once from the linear response of its last converged preview ("linear") and solves the
// newest one ("converged" replaces it), so the face follows the hand without a backlog.
"use strict";

const AXES = [
  { key: "anterior_mm", label: "Advancement (+) / setback (−)", unit: "mm", range: 15, step: 0.5 },
  { key: "superior_mm", label: "Impaction (+) / downgraft (−)", unit: "mm", range: 15, step: 0.5 },
  { key: "right_mm", label: "Lateral shift (right +)", unit: "mm", range: 15, step: 0.5 },
  { key: "pitch_deg", label: "Pitch (front up +)", unit: "°", range: 15, step: 0.5 },
  { key: "roll_deg", label: "Roll (right side up +)", unit: "°", range: 15, step: 0.5 },
  { key: "yaw_deg", label: "Yaw (front to right +)", unit: "°", range: 15, step: 0.5 },
];
const LANDMARK_NAMES = {
  pronasale: "nose tip (pronasale)", subnasale: "subnasale", labrale_superius: "upper lip (labrale sup.)",
  stomion: "stomion", labrale_inferius: "lower lip (labrale inf.)", soft_pogonion: "chin (soft pogonion)",
  soft_menton: "soft menton",
};

const $ = (id) => document.getElementById(id);
const state = {
  ws: null, caseId: null, fragments: [], poses: {}, limits: { translation_mm: 30, rotation_deg: 30 },
  posesDirty: false, sendTimer: null, lastSend: -Infinity, job: null, nextId: 1, viewInFlight: false,
  pendingView: null, lastFrameUrl: null, frameTimes: [], lastSolve: null, openAfterList: null, reconnected: false, session: null, formerSession: null,
  frameSize: null, lastFigures: null,
  pendingSave: null, askReplace: null, planDetails: new Map(),  // a save_plan awaiting its reply; a replace to ask
};
const SEND_INTERVAL_MS = 50;  // at most 20 pose updates a second while dragging

function token() {
  const p = new URLSearchParams(location.hash.slice(1) || location.search.slice(1));
  return p.get("token");
}

function say(text, kind = "info") {
  const line = document.createElement("div");
  line.className = kind;
  line.textContent = `${new Date().toLocaleTimeString()} ${text}`;
  $("messages").prepend(line);
  while ($("messages").childElementCount > 30) $("messages").lastChild.remove();
}

function send(message) {
  if (!state.ws || state.ws.readyState !== WebSocket.OPEN) return say("not connected to the server", "error");
  message.id = state.nextId++;
  state.ws.send(JSON.stringify(message));
  return message.id;
}

// ---- connection -----------------------------------------------------------------------------

function connect() {
  const t = token();
  const url = `${location.protocol === "https:" ? "wss" : "ws"}://${location.host}/ws${t ? "?token=" + encodeURIComponent(t) : ""}`;
  const ws = new WebSocket(url);
  ws.binaryType = "blob";
  state.ws = ws;
  ws.onopen = () => {
    $("connection").textContent = "connected";
    state.reconnected = true;
    send({ type: "list_cases" });
  };
  ws.onclose = () => {
    $("connection").textContent = "disconnected — reconnecting…";
    setEnabled(false);
    setTimeout(connect, 2000);
  };
  ws.onmessage = (event) => (typeof event.data === "string" ? onMessage(JSON.parse(event.data)) : onFrame(event.data));
}

const handlers = {
  welcome: (m) => {
    state.limits = m.limits;
    // After a reconnect the former session's fine jobs are resumed once the case is open again
    // (the first former one: a session that dropped again before opening the case holds none).
    if (state.session && state.session !== m.session && !state.formerSession) state.formerSession = state.session;
    state.session = m.session;
  },
  cases: (m) => {
    // Names and descriptions are the case files' (an upload's name is any text): options as text.
    $("case-select").replaceChildren(...m.cases.map((c) => new Option(`${c.name} — ${c.description}`, c.id)));
    // A patient just imported opens at once; after a reconnect the case that was open opens again.
    const next = state.openAfterList || (state.reconnected ? state.caseId : null);
    state.openAfterList = null;
    state.reconnected = false;
    if (next) { $("case-select").value = next; openCase(next); }
  },
  opening: (m) => say(`opening ${m.case}…`),
  opened: (m) => { onOpened(m); showCaseEditor(m); showFaceTargets(m); },
  open_progress: (m) => onOpenProgress(m),
  case_edited: (m) => say(`case ${m.case} changed; rebuilding it`),
  case: () => {},
  poses: (m) => showWarnings(m.warnings || []),
  loaded: (m) => { state.poses = m.poses; renderFragments(); say(`plan "${m.name}" loaded`); },
  preview: (m) => onPreview(m),
  preview_failed: (m) => { showSolveState(null); say(m.message, "error"); },
  face_fitting: (m) => onFaceFitting(m),
  face_progress: (m) => onFaceProgress(m),
  face_plan: (m) => onFacePlan(m),
  face_plan_failed: (m) => onFacePlanFailed(m),
  drag_ready: () => {},
  drag_unavailable: (m) => say(`the drag view is off until the next preview: ${m.message}`, "error"),
  job_queued: (m) => onJob(m, `queued (${m.position} ahead)`, 0),
  job_progress: (m) => onJob(m, `${m.phase}…`, m.fraction),
  job_done: (m) => onJobDone(m),
  job_cancelled: (m) => onJobEnd(m, "cancelled"),
  resumed: (m) => {
    for (const j of m.jobs) onJob(j, `resumed after the reconnect (${j.phase || j.state})`, j.fraction || 0);
    if (m.jobs.length) say(`${m.jobs.length} fine job(s) of the last connection resumed`);
  },
  job_failed: (m) => onJobEnd(m, m.message),
  cancelling: () => {},
  saved: (m) => { say(`plan "${m.name}" saved ${savedBy(m)}`); send({ type: "list_plans" }); },
  plans: (m) => onPlans(m),
  exported: (m) => {
    const a = $("download");
    a.href = m.url + (token() ? "?token=" + encodeURIComponent(token()) : "");
    a.download = m.file_name;
    a.textContent = `download ${m.file_name} (${(m.bytes / 1e6).toFixed(1)} MB)`;
    a.hidden = false;
  },
  picked: (m) => { if (!placeLandmark(m)) onPicked(m); },
  frame: (m) => {
    state.frameSize = [m.width, m.height];
    const now = performance.now();
    state.frameTimes = state.frameTimes.filter((t) => now - t < 1000).concat(now);  // frames in the last second
    $("frame-info").textContent = `${m.view} view, colour map: ${m.colormap}, ${m.width}×${m.height}, drawn in ${m.render_ms.toFixed(0)} ms, ${state.frameTimes.length} fps`;
    if (m.shows) showSolveState(m.shows.state);
  },
  error: (m) => {
    if (m.error === "unknown_type" && /view/.test(m.message)) return;  // a server without rendering
    if (m.error === "edit_failed") onEditFailed(m);
    if (m.error === "plan_exists" && state.pendingSave && m.id === state.pendingSave.id) return onPlanExists(m);
    say(m.message, "error");
  },
};

function onMessage(m) {
  const handler = handlers[m.type];
  if (handler) handler(m);
}

function onFrame(blob) {
  const url = URL.createObjectURL(blob);
  $("frame").src = url;
  if (state.lastFrameUrl) URL.revokeObjectURL(state.lastFrameUrl);
  state.lastFrameUrl = url;
  $("frame-hint").hidden = true;
  state.viewInFlight = false;
  flushView();
}

// ---- case and fragments -----------------------------------------------------------------------

function openCase(id) {
  state.caseId = id;
  send({ type: "open", case: id });
}

function onOpened(m) {
  state.caseId = m.case;
  state.fragments = m.fragments;
  state.poses = {};
  for (const f of m.fragments) state.poses[f.name] = { ...f.pose };
  renderFragments();
  setEnabled(true);
  say(`${m.name} open (${m.coarse.tetrahedra} tetrahedra in the coarse model, ${m.seconds.toFixed(1)} s)`);
  send({ type: "list_plans" });
  if (state.formerSession) {
    send({ type: "resume", session: state.formerSession });
    state.formerSession = null;
  }
  sendView({ size: frameSize() });
  send({ type: "preview" });
}

function renderFragments() {
  const box = $("fragments");
  box.replaceChildren();
  for (const f of state.fragments) {
    const div = document.createElement("div");
    div.className = "fragment";
    div.dataset.fragment = f.name;
    const head = document.createElement("div");
    head.className = "fragment-head";
    const title = document.createElement("span");
    title.textContent = f.name.replace(/_/g, " ");  // a case file's name: text, never markup
    head.append(title);
    const reset = document.createElement("button");
    reset.textContent = "reset";
    reset.onclick = () => { for (const a of AXES) state.poses[f.name][a.key] = 0; renderFragments(); posesChanged(); };
    head.append(reset);
    div.append(head);
    for (const a of AXES) div.append(axisControl(f.name, a));
    box.append(div);
  }
}

function axisControl(fragment, axis) {
  const row = document.createElement("label");
  row.className = "axis";
  const limit = axis.unit === "mm" ? state.limits.translation_mm : state.limits.rotation_deg;
  const value = state.poses[fragment][axis.key] || 0;
  const slider = Object.assign(document.createElement("input"), {
    type: "range", min: -axis.range, max: axis.range, step: axis.step, value,
  });
  slider.setAttribute("aria-label", `${fragment} ${axis.key}`);
  slider.dataset.fragment = fragment;
  slider.dataset.axis = axis.key;
  const number = Object.assign(document.createElement("input"), {
    type: "number", min: -limit, max: limit, step: axis.step, value,
  });
  const set = (v, from) => {
    if (!Number.isFinite(v) || Math.abs(v) > limit) return say(`${axis.label}: enter a number within ±${limit} ${axis.unit}`, "error");
    state.poses[fragment][axis.key] = v;
    if (from !== slider) slider.value = v;
    if (from !== number) number.value = v;
    posesChanged();
  };
  slider.oninput = () => set(Number(slider.value), slider);
  number.onchange = () => set(Number(number.value), number);
  row.append(Object.assign(document.createElement("span"), { textContent: axis.label }), slider, number,
    Object.assign(document.createElement("span"), { textContent: axis.unit }));
  return row;
}

// Newest wins on the server; here the poses go out at most every SEND_INTERVAL_MS, the last
// change always (a trailing send).
function posesChanged() {
  state.posesDirty = true;
  if (state.sendTimer) return;
  const wait = state.lastSend + SEND_INTERVAL_MS - performance.now();
  // The first change of a drag goes out at once (not from a timer, which a fast burst of input
  // events can overtake); later ones wait for the interval.
  if (wait <= 0) return flushPoses();
  state.sendTimer = setTimeout(flushPoses, wait);
}

function flushPoses() {
  state.sendTimer = null;
  if (!state.posesDirty) return;
  state.posesDirty = false;
  state.lastSend = performance.now();
  send({ type: "set_poses", poses: state.poses });
}

// What the face shows: the linear drag view while the preview refines, or the converged solve.
function showSolveState(shown) {
  const last = state.lastSolve;
  const solved = last ? `last solve ${last.seconds.toFixed(2)} s at ${last.at}` : "no solve yet";
  const text = {
    linear: `linear drag view, refining… (${solved})`, converged: `converged (${solved})`, rest: "rest pose",
    band_low: "prediction band: low envelope", band_high: "prediction band: high envelope",
    band_nominal: "prediction band: nominal prediction",
    face_fit: "moving the bones to reach the face targets…",
  };
  $("solve-state").textContent = text[shown] || solved;
  $("solve-state").dataset.state = shown || "";
}

function onPreview(m) {
  const f = m.figures;
  state.lastFigures = f;
  state.lastSolve = { seconds: f.solve_s, at: new Date().toLocaleTimeString() };
  const table = document.createElement("table");
  tableRow(table, "th", ["landmark", "forward", "up", "right"]);
  for (const [name, label] of Object.entries(LANDMARK_NAMES)) {
    const l = f.landmarks[name];
    if (l) tableRow(table, "td", [label, l.anterior_mm.toFixed(2), l.superior_mm.toFixed(2), l.right_mm.toFixed(2)]);
  }
  const time = element("p", "", "Solved in ", element("b", "", `${f.solve_s.toFixed(2)} s`),
    ` (${f.iterations} Newton iterations); skin moved up to ${f.max_skin_displacement_mm.toFixed(1)} mm.` +
    (f.linear_error ? ` The drag view was off by up to ${f.linear_error.max_mm.toFixed(2)} mm` +
      (f.linear_error.lips_mm !== undefined ? ` (lips ${f.linear_error.lips_mm.toFixed(2)} mm)` : "") + "." : ""));
  time.id = "solve-time";
  $("preview-figures").replaceChildren(time, table);
  appendSolveWarnings($("preview-figures"), f.warnings);
}

// An element of `tag` with class `className` holding `parts`: strings (as text) and elements. The
// page builds everything this way; nothing it shows is parsed as markup.
function element(tag, className, ...parts) {
  const e = document.createElement(tag);
  if (className) e.className = className;
  e.append(...parts);
  return e;
}

// A row of `cells` (texts) in `table`, as `tag` ("th" or "td") cells.
function tableRow(table, tag, cells) {
  const row = table.insertRow();
  for (const text of cells) row.append(element(tag, "", text));
  return row;
}

// What the solver says about the result itself (e.g. bone pieces that overlap), as text.
function appendSolveWarnings(box, warnings) {
  for (const w of warnings || []) {
    const p = document.createElement("p");
    p.className = "warning solve-warning";
    p.textContent = w;
    box.append(p);
  }
}

function showWarnings(warnings) {
  $("warnings").hidden = warnings.length === 0;
  $("warnings").textContent = warnings.join("; ");
}

// ---- fine jobs ------------------------------------------------------------------------------

function onJob(m, text, fraction) {
  state.job = m.job;
  $("job-progress").hidden = false;
  $("job-progress").value = fraction;
  $("job-status").textContent = `Fine job ${m.job}: ${text} ${Math.round(fraction * 100)}%`;
  $("cancel-job").disabled = false;
}

function onJobDone(m) {
  onJob(m, "done", 1);
  $("cancel-job").disabled = true;
  const d = m.coarse_vs_fine;
  $("job-status").textContent = `Fine job ${m.job} done in ${m.figures.time_s.toFixed(1)} s ` +
    `(${m.figures.tetrahedra} tetrahedra).` + (d && d.max_mm !== undefined
      ? ` Coarse vs fine on the skin: mean ${d.mean_mm.toFixed(2)} mm, 95% within ${d.p95_mm.toFixed(2)} mm, max ${d.max_mm.toFixed(2)} mm.`
      : "");
  appendSolveWarnings($("job-status"), m.figures.warnings);
  $("colormap").value = "difference";
  sendView({ colormap: "difference" });
}

function onJobEnd(m, why) {
  $("job-status").textContent = `Fine job ${m.job}: ${why}`;
  $("job-progress").hidden = true;
  $("cancel-job").disabled = true;
}

// ---- view -----------------------------------------------------------------------------------

function frameSize() {
  const r = $("frame-box").getBoundingClientRect();
  return [Math.max(320, Math.min(1600, Math.round(r.width))), Math.max(240, Math.min(1200, Math.round(r.height)))];
}

// Camera changes merge while a frame is on its way: the server renders the newest only anyway.
function sendView(change) {
  // orbit, pan (relative) and zoom (a factor) arrive already summed with the pending ones.
  state.pendingView = { ...(state.pendingView || {}), ...change };
  flushView();
}

function flushView() {
  if (state.viewInFlight || !state.pendingView || !state.caseId) return;
  state.viewInFlight = true;
  send({ type: "view", ...state.pendingView });
  state.pendingView = null;
  setTimeout(() => { state.viewInFlight = false; flushView(); }, 1000);  // never stall on a lost frame
}

function setupViewer() {
  const box = $("frame-box");
  let drag = null;
  box.onpointerdown = (e) => {
    drag = { x: e.clientX, y: e.clientY, pan: e.shiftKey, startX: e.clientX, startY: e.clientY };
    box.setPointerCapture(e.pointerId);
  };
  box.onpointerup = (e) => {
    // A click (no drag) picks what the frame shows under the pointer.
    if (drag && Math.hypot(e.clientX - drag.startX, e.clientY - drag.startY) < 3) pickAt(e.clientX, e.clientY);
    drag = null;
  };
  box.onpointermove = (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    const prev = state.pendingView || {};
    if (drag.pan) {
      const p = prev.pan || [0, 0];
      sendView({ pan: [p[0] + dx, p[1] + dy] });
    } else {
      const o = prev.orbit || [0, 0];
      sendView({ orbit: [o[0] - dx * 0.4, o[1] + dy * 0.4] });  // degrees: the face turns with the mouse
    }
  };
  box.onwheel = (e) => {
    e.preventDefault();
    const z = (state.pendingView && state.pendingView.zoom) || 1;
    sendView({ zoom: z * Math.exp(-e.deltaY * 0.001) });
  };
  for (const b of document.querySelectorAll("#views button")) b.onclick = () => sendView({ preset: b.dataset.view });
  $("colormap").onchange = () => sendView({ colormap: $("colormap").value });
  // Bones are inside the skin: showing them makes the skin translucent (and a click then picks the
  // bone under the pointer, for hard-tissue landmarks).
  $("show-bones").onchange = () => sendView({ bones: $("show-bones").checked, skin_opacity: $("show-bones").checked ? 0.35 : 1 });
  $("show-landmarks").onchange = () => sendView({ landmarks: $("show-landmarks").checked });
  $("before-after").onchange = () => sendView({ before_after: $("before-after").checked });
  window.addEventListener("resize", () => state.caseId && sendView({ size: frameSize() }));
}

// The frame's pixel under a client position: the image is letterboxed (object-fit: contain).
function pickAt(clientX, clientY) {
  if (!state.caseId || !state.frameSize) return;
  const r = $("frame").getBoundingClientRect();
  const [w, h] = state.frameSize;
  const scale = Math.min(r.width / w, r.height / h);
  const x = (clientX - r.left - (r.width - w * scale) / 2) / scale;
  const y = (clientY - r.top - (r.height - h * scale) / 2) / scale;
  if (x < 0 || y < 0 || x > w || y > h) return;
  send({ type: "pick", x, y });
}

function onPicked(m) {
  const mm = (p) => p.map((v) => v.toFixed(1)).join(", ");
  $("pick-info").textContent = m.surface
    ? `picked ${m.surface} at (${mm(m.point_mm)}) mm; at rest (${mm(m.rest_mm)}) mm`
    : "nothing under that pixel";
}

// ---- plans ----------------------------------------------------------------------------------

const USER_NAME_KEY = "orthosim.userName";

// "by Ada at 2025-05-01T09:30:00Z": who saved a plan and when, as `saved` and list_plans give it.
function savedBy(p) {
  return `by ${p.saved_by || "someone who gave no name"}${p.saved_at ? ` at ${p.saved_at}` : ""}`;
}

function onPlans(m) {
  const details = new Map((m.details || []).map((d) => [d.name, d]));
  state.planDetails = details;
  $("plan-list").replaceChildren(...m.plans.map((name) =>
    new Option(details.has(name) ? `${name} (${savedBy(details.get(name))})` : name, name)));
  $("load-plan").disabled = m.plans.length === 0;
  if (state.askReplace) askReplace(state.askReplace, details.get(state.askReplace.name));
}

function savePlan(name, replace) {
  const message = { type: "save_plan", name };
  const user = $("user-name").value.trim();
  if (user) message.saved_by = user;
  if (replace) message.replace = true;
  state.pendingSave = { name, id: send(message) };
}

// The name is saved already (perhaps by another surgeon since this page listed the plans): the
// current list says by whom and when, then the surgeon decides.
function onPlanExists(m) {
  state.askReplace = { name: state.pendingSave.name, message: m.message };
  state.pendingSave = null;
  send({ type: "list_plans" });
}

function askReplace(ask, detail) {
  state.askReplace = null;
  const who = detail ? `Plan "${ask.name}" was saved ${savedBy(detail)}.` : ask.message;
  if (confirm(`${who}\n\nReplace it with the current plan?`)) savePlan(ask.name, true);
  else say(`plan "${ask.name}" not saved: the saved one is kept`);
}

function setupUserName() {
  const field = $("user-name");
  try { field.value = localStorage.getItem(USER_NAME_KEY) || ""; } catch (e) { /* storage off: ask each time */ }
  field.oninput = () => {
    try { localStorage.setItem(USER_NAME_KEY, field.value.trim()); } catch (e) { /* kept for this page only */ }
  };
}

// ---- buttons --------------------------------------------------------------------------------

function setEnabled(on) {
  for (const id of ["confirm", "save-plan", "export"]) $(id).disabled = !on;
}

function setupButtons() {
  $("open-case").onclick = () => openCase($("case-select").value);
  $("confirm").onclick = () => send({ type: "confirm" });
  $("cancel-job").onclick = () => state.job && send({ type: "cancel", job: state.job });
  $("save-plan").onclick = () => {
    const name = $("plan-name").value.trim();
    if (!/^[A-Za-z0-9][A-Za-z0-9_-]{0,63}$/.test(name))
      return say("plan names are 1-64 letters, digits, '_' or '-', starting with a letter or digit", "error");
    savePlan(name, false);
  };
  $("load-plan").onclick = () => send({ type: "load_plan", name: $("plan-list").value });
  $("export").onclick = () => send({ type: "export", format: $("export-format").value, result: $("export-result").value });
}

setupViewer();
setupButtons();
setupUserName();
connect();
