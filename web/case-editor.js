// "Landmarks and osteotomies" of an imported patient (docs/protocol.md, edit_case): landmarks are
// placed by clicking the face (the server picks the skin under the pixel and answers with its rest
// position), osteotomy templates are chosen and their levels shifted, and Apply sends the changes;
// the server rewrites the case and opens it again, with its progress shown.
"use strict";

const TEMPLATES = [
  { kind: "le_fort_1", label: "Le Fort I", offset: 4, hint: "mm above the upper incisor apex", tilts: true },
  { kind: "le_fort_2", label: "Le Fort II", offset: 8, hint: "mm below nasion" },
  { kind: "segmented_maxilla", label: "segmented maxilla", offset: 4, hint: "mm above the upper incisor apex", tilts: true },
  { kind: "bsso", label: "BSSO", offset: 12, hint: "mm behind the lower first molars" },
  { kind: "usso", side: "left", label: "USSO left", offset: 12, hint: "mm behind the lower first molar" },
  { kind: "usso", side: "right", label: "USSO right", offset: 12, hint: "mm behind the lower first molar" },
  { kind: "genioplasty", label: "genioplasty", offset: 5, hint: "mm below the mental foramina", tilts: true },
];
const editor = { landmarks: {}, pending: {}, placing: null, cuts: [], needed: {} };

function showCaseEditor(m) {
  const rebuilt = !$("rebuild-progress").hidden;
  $("case-editor").hidden = !m.editable;
  $("rebuild-progress").hidden = true;
  if (!m.editable) return;
  if (rebuilt) $("edit-status").textContent = `case rebuilt and opened in ${m.seconds.toFixed(1)} s`;
  editor.landmarks = m.landmarks_mm || {};
  editor.pending = {};
  editor.placing = null;
  editor.cuts = m.cuts || [];
  editor.needed = {};
  for (const n of m.landmarks_needed || []) editor.needed[n.name] = n.by;
  showFrame(m);
  renderLandmarks();
  renderCutEditor();
}

function showFrame(m) {
  const v = (a) => `(${a.map((x) => x.toFixed(2)).join(", ")})`;
  const f = m.frame;
  const from = m.frame_from_landmarks
    ? "from the Frankfort horizontal (porions, orbitale)"
    : "the files' axes: place porion_left, porion_right and an orbitale to derive it";
  $("frame-status").textContent = `Anatomical frame: anterior ${v(f.anterior)}, superior ${v(f.superior)}; ${from}.`;
}

// The needed landmarks first (what the cuts, the frame and the figures read), then the others.
function renderLandmarks() {
  const table = $("landmark-table");
  table.replaceChildren();
  tableRow(table, "th", ["landmark", "needed by", "at rest (mm)", ""]);
  const all = [...new Set([...Object.keys(editor.needed), ...Object.keys(editor.landmarks), ...Object.keys(editor.pending)])];
  const names = all.sort((a, b) => (Boolean(editor.needed[b]) - Boolean(editor.needed[a])) || a.localeCompare(b));
  for (const name of names) {
    const row = table.insertRow();
    const p = editor.pending[name] || editor.landmarks[name];
    row.insertCell().textContent = name + (editor.pending[name] ? " (new place)" : "");
    row.insertCell().textContent = (editor.needed[name] || []).join(", ");
    row.insertCell().textContent = p ? p.map((v) => v.toFixed(1)).join(", ") : "not placed";
    if (!p) row.className = "missing";
    const button = document.createElement("button");
    button.textContent = editor.placing === name ? "click the face…" : "Place";
    button.dataset.landmark = name;
    button.onclick = () => startPlacing(name);
    row.insertCell().append(button);
  }
}

function startPlacing(name) {
  editor.placing = name;
  if (!$("show-landmarks").checked) {  // placing one: show where the others are
    $("show-landmarks").checked = true;
    sendView({ landmarks: true });
  }
  renderLandmarks();
  $("edit-status").textContent = `click where ${name} lies (tick "bones" to click on the bones)`;
}

// A pick while a landmark is being placed places it; returns whether it took the pick.
function placeLandmark(m) {
  if (!editor.placing) return false;
  if (!m.surface) {
    $("edit-status").textContent = "nothing under that pixel: click on the face";
    return true;
  }
  editor.pending[editor.placing] = m.rest_mm;
  $("edit-status").textContent = `${editor.placing} placed; Apply to rebuild the case`;
  editor.placing = null;
  renderLandmarks();
  return true;
}

const templateKey = (t) => (t.side ? `${t.kind}_${t.side}` : t.kind);

function renderCutEditor() {
  const box = $("cut-editor");
  box.replaceChildren();
  // An input of `type` with `attributes` (data-* and aria-label as attributes, the rest as properties).
  const input = (type, attributes, props) => {
    const e = Object.assign(document.createElement("input"), { type, ...props });
    for (const [name, value] of Object.entries(attributes)) e.setAttribute(name, value);
    return e;
  };
  for (const t of TEMPLATES) {
    const current = editor.cuts.find((c) => c.kind === t.kind && (!t.side || c.side === t.side));
    const key = templateKey(t);
    const row = element("label", "row",
      input("checkbox", { "data-kind": key, "aria-label": `cut ${key}` }, { checked: Boolean(current) }), ` ${t.label} `,
      input("number", { "data-offset": key, "aria-label": `${key} offset` }, {
        step: 0.5, min: 0, max: 50, value: current && current.offset_mm !== undefined ? current.offset_mm : t.offset,
      }), ` ${t.hint}`);
    if (t.tilts)
      row.append("; tilt ", input("number", { "data-tilt": key, "aria-label": `${key} tilt` }, {
        step: 1, min: -30, max: 30, value: current && current.tilt_deg !== undefined ? current.tilt_deg : 0,
      }), "° (+ front up)");
    box.append(row);
  }
}

function applyEdit() {
  const cuts = [];
  for (const t of TEMPLATES) {
    const key = templateKey(t);
    if (!document.querySelector(`#cut-editor input[data-kind="${key}"]`).checked) continue;
    const offset = Number(document.querySelector(`#cut-editor input[data-offset="${key}"]`).value);
    const cut = { kind: t.kind, offset_mm: offset };
    if (t.side) cut.side = t.side;
    const tilt = t.tilts ? Number(document.querySelector(`#cut-editor input[data-tilt="${key}"]`).value) : 0;
    if (tilt) cut.tilt_deg = tilt;
    cuts.push(cut);
  }
  const message = { type: "edit_case", cuts };
  if (Object.keys(editor.pending).length) message.landmarks = editor.pending;
  send(message);
  $("rebuild-progress").hidden = false;
  $("rebuild-progress").value = 0;
  $("edit-status").textContent = "rewriting the case…";
}

function onEditFailed(m) {
  $("rebuild-progress").hidden = true;
  $("edit-status").textContent = m.message;
}

function onOpenProgress(m) {
  const bar = $("rebuild-progress");
  bar.value = m.fraction;
  $("edit-status").textContent = `rebuilding: ${m.phase === "mesh" ? "tissue mesh" : "solver model"}…`;
  if (!$("case-editor").hidden) bar.hidden = false;
  say(`opening ${m.case}: ${m.phase}`);
}

$("apply-edit").onclick = applyEdit;
$("add-landmark").onclick = () => {
  const name = $("new-landmark").value.trim();
  if (!/^[A-Za-z0-9][A-Za-z0-9_-]{0,63}$/.test(name)) return say("landmark names are 1-64 letters, digits, '_' or '-'", "error");
  startPlacing(name);
};
