// "Plan from the face" (docs/protocol.md, plan_from_face): the surgeon types where soft-tissue
// landmarks should go (mm from their pre-operative place, forward / up / right, each with a weight),
// locks the pose values the bones must keep, and the server finds the fragment poses that reach the
// targets. Each iteration is drawn as the bones move; the poses found go into the sliders and the
// plan like any other, and their converged preview follows.
"use strict";

const FACE_AXES = [["anterior_mm", "forward"], ["superior_mm", "up"], ["right_mm", "right"]];
const face = { landmarks: [], fitting: false };

function faceLabel(name) { return LANDMARK_NAMES[name] || name.replace(/_/g, " "); }

// An element with attributes and children; text goes in as text, never as markup (names come from
// users' files).
function faceEl(tag, attrs = {}, children = []) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (v === true) e.setAttribute(k, "");
    else if (v !== false && v !== undefined) e.setAttribute(k, String(v));
  }
  for (const c of children) e.append(c);
  return e;
}

function faceTargetRow(name) {
  const cells = FACE_AXES.map(([key, label]) => faceEl("td", {}, [faceEl("input", {
    type: "number", step: "0.5", min: "-50", max: "50", value: "0", "data-landmark": name, "data-axis": key,
    "aria-label": `${name} target ${label}`, disabled: true,
  })]));
  const box = faceEl("input", { type: "checkbox", "data-target": name, "aria-label": `target ${name}` });
  box.onchange = () => enableTarget(name, box.checked);
  const weight = faceEl("input", {
    type: "number", step: "0.5", min: "0.001", max: "1000", value: "1", "data-weight": name,
    "aria-label": `${name} weight`, disabled: true,
  });
  return faceEl("tr", {}, [faceEl("td", {}, [faceEl("label", {}, [box, ` ${faceLabel(name)}`])]), ...cells,
    faceEl("td", {}, [weight]), faceEl("td", { class: "miss", "data-miss": name })]);
}

function showFaceTargets(m) {
  face.landmarks = m.face_landmarks || [];
  $("face-targets").hidden = face.landmarks.length === 0;
  const head = faceEl("tr", {}, ["landmark", "forward", "up", "right", "weight", "miss"].map((h) => faceEl("th", {}, [h])));
  $("face-target-table").replaceChildren(head, ...face.landmarks.map(faceTargetRow));
  renderFaceLocks(m.fragments || []);
  $("face-status").textContent = "";
}

// Ticking a landmark starts its target where the newest preview has it, so only the change is typed.
function enableTarget(name, on) {
  const shown = state.lastFigures && state.lastFigures.landmarks && state.lastFigures.landmarks[name];
  for (const input of document.querySelectorAll(`#face-target-table input[data-landmark="${name}"], #face-target-table input[data-weight="${name}"]`)) {
    input.disabled = !on;
    if (on && shown && input.dataset.axis) input.value = shown[input.dataset.axis].toFixed(1);
  }
}

// The proximal segments of a split follow the condyles, which the face does not show: locked at first.
function renderFaceLocks(fragments) {
  const rows = fragments.map((f) => {
    const locked = /^ramus/.test(f.name);
    const boxes = AXES.map((a) => faceEl("label", { title: a.label }, [faceEl("input", {
      type: "checkbox", "data-lock": f.name, "data-axis": a.key, checked: locked, "aria-label": `lock ${f.name} ${a.key}`,
    }), a.key.replace(/_(mm|deg)$/, "")]));
    const parts = [faceEl("span", {}, [f.name.replace(/_/g, " ")])];
    for (const box of boxes) parts.push(" ", box);
    return faceEl("div", { class: "lock-row" }, parts);
  });
  $("face-locks").replaceChildren(...rows);
}

function faceRequest() {
  const targets = {};
  for (const box of document.querySelectorAll("#face-target-table input[data-target]:checked")) {
    const name = box.dataset.target;
    const t = {};
    for (const input of document.querySelectorAll(`#face-target-table input[data-landmark="${name}"]`)) {
      const v = Number(input.value);
      if (!Number.isFinite(v) || Math.abs(v) > 50) throw new Error(`${faceLabel(name)}: a target within ±50 mm`);
      t[input.dataset.axis] = v;
    }
    const w = Number(document.querySelector(`#face-target-table input[data-weight="${name}"]`).value);
    if (!(w > 0)) throw new Error(`${faceLabel(name)}: a weight above 0`);
    t.weight = w;
    targets[name] = t;
  }
  if (Object.keys(targets).length === 0) throw new Error("tick at least one landmark to target");
  const locks = {};
  for (const box of document.querySelectorAll("#face-locks input[data-lock]:checked"))
    (locks[box.dataset.lock] = locks[box.dataset.lock] || []).push(box.dataset.axis);
  return { targets, locks, from: $("face-from-rest").checked ? "rest" : "current" };
}

function findPoses() {
  let request;
  try {
    request = faceRequest();
  } catch (e) {
    return say(e.message, "error");
  }
  for (const cell of document.querySelectorAll("#face-target-table td[data-miss]")) cell.textContent = "";
  send({ type: "plan_from_face", ...request });
}

function onFaceFitting(m) {
  face.fitting = true;
  $("find-poses").disabled = true;
  $("face-status").textContent = `finding poses for ${m.targets} target(s)…`;
}

function onFaceProgress(m) {
  $("face-status").textContent = `iteration ${m.iteration}: largest miss ${m.largest_miss_mm.toFixed(2)} mm`;
}

function onFacePlan(m) {
  face.fitting = false;
  $("find-poses").disabled = false;
  for (const r of m.residuals || []) {
    const cell = document.querySelector(`#face-target-table td[data-miss="${r.landmark}"]`);
    if (cell) cell.textContent = `${r.distance_mm.toFixed(2)} mm`;
  }
  const status = $("face-status");
  status.className = m.reached ? "figures" : "figures warning";
  status.textContent = `${m.message} (${m.solves} solves, ${m.time_s.toFixed(1)} s)`;
  if (m.cancelled) return;
  // The server has taken these poses; the sliders show them and the preview of them follows.
  state.poses = m.poses;
  renderFragments();
  showWarnings(m.warnings || []);
  say(m.reached ? "poses found from the face targets" : "the face targets cannot all be reached; the best poses are shown");
}

function onFacePlanFailed(m) {
  face.fitting = false;
  $("find-poses").disabled = false;
  $("face-status").className = "figures warning";
  $("face-status").textContent = m.message;
}

$("find-poses").onclick = findPoses;
