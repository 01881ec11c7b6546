// The accuracy report: the last `orthosim bench cohort` run written into web/cohort/ (its JSON
// and speed-versus-error plot), shown as the paper's Table 4 (with the lips' and soft chin's
// distance to the reference) and the soft-to-hard ratios with their plausibility flags. Loaded only
// when the clinician opens the report.
"use strict";

const REPORT_JSON = "cohort/cohort.json";
const REPORT_PLOT = "cohort/speed-error.png";
// The report format this page reads: the bench's kCohortReportSchemaVersion (engine/eval/CohortJson.hpp).
const REPORT_SCHEMA_VERSION = 1;
// Table 4's landmarks (the bench's cohortTableLandmarks, engine/eval/CohortRun.hpp), from each
// run's landmark_error_mm.
const REPORT_LANDMARKS = [
  { name: "labrale_inferius", label: "Li" },
  { name: "labrale_superius", label: "Ls" },
  { name: "soft_pogonion", label: "Pog'" },
];
const LANDMARK_WORDS = {
  labrale_inferius: "lower lip (labrale inferius)",
  labrale_superius: "upper lip (labrale superius)",
  soft_pogonion: "soft pogonion",
};
// A landmark this far from the reference or farther is shown in red (mm).
const LANDMARK_FLAG_MM = 1;

function reportCell(row, text, className) {
  const cell = document.createElement(row.parentElement && row.parentElement.tagName === "THEAD" ? "th" : "td");
  cell.textContent = text;
  if (className) cell.className = className;
  row.append(cell);
  return cell;
}

// head: the column titles; groups (optional): a row above them of [title, columns spanned].
function reportTable(head, rows, groups) {
  const table = document.createElement("table");
  const thead = table.createTHead();
  if (groups) {
    const gr = thead.insertRow();
    groups.forEach(([title, span]) => (reportCell(gr, title).colSpan = span));
  }
  const hr = thead.insertRow();
  head.forEach((h) => (Array.isArray(h) ? (reportCell(hr, h[0]).title = h[1]) : reportCell(hr, h)));
  const body = table.createTBody();
  rows.forEach((r) => {
    const tr = body.insertRow();
    r.forEach((c) => (Array.isArray(c) ? reportCell(tr, c[0], c[1]) : reportCell(tr, c)));
  });
  return table;
}

const pct = (share) => (share === undefined ? "—" : `${(100 * share).toFixed(1)} %`);
const secs = (s) => (s === undefined ? "—" : s.toFixed(2));

// A landmark's distance to the reference (mm), red from LANDMARK_FLAG_MM on; "—" when not measured.
function landmarkCell(run, name) {
  const d = run.landmark_error_mm ? run.landmark_error_mm[name] : undefined;
  if (typeof d !== "number") return "—";
  return [d.toFixed(2), d >= LANDMARK_FLAG_MM ? "flag" : ""];
}

// Table 4: per patient, coarse and fine against the reference: triangles, solve time, the face's
// area within 1 and 3 mm, and the distance at the lips and soft pogonion.
function tableFour(report) {
  const landmarks = REPORT_LANDMARKS;
  const runColumns = 4 + landmarks.length;
  const runCells = (r) => [r.skin_triangles, secs(r.solve_s), pct(r.face_region.share_within[0]),
    pct(r.face_region.share_within[2]), ...landmarks.map((l) => landmarkCell(r, l.name))];
  const rows = report.patients.map((p) => {
    if (p.error) return [p.id, p.procedure, ["not measured: " + p.error, "flag"], ...Array(2 * runColumns - 1).fill("")];
    return [p.id, `${p.diagnosis}: ${p.procedure}`, ...runCells(p.coarse), ...runCells(p.fine)];
  });
  const within = (mm) => [`≤${mm} mm`, `share of the face region's skin area within ${mm} mm of the reference`];
  const runHead = ["triangles", "solve s", within(1), within(3),
    ...landmarks.map((l) => [l.label, `${LANDMARK_WORDS[l.name]}: distance to the reference, mm`])];
  const table = reportTable(["patient", "procedure", ...runHead, ...runHead], rows,
    [["", 2], ["coarse", runColumns], ["fine", runColumns]]);
  table.id = "report-table4";
  // A rule before each run's columns.
  for (const tr of table.querySelectorAll("tbody tr, thead tr:last-child"))
    for (const k of [2, 2 + runColumns]) if (tr.cells[k]) tr.cells[k].classList.add("run-start");
  return table;
}

// What Table 4's columns measure.
function tableFourNote() {
  const note = document.createElement("p");
  note.className = "hint";
  note.id = "report-table4-note";
  const names = REPORT_LANDMARKS.map((l) => `${l.label}: ${LANDMARK_WORDS[l.name]}`).join(", ");
  note.textContent = "≤1 mm, ≤3 mm: share of the face region's skin area within 1 / 3 mm of the reference. " +
    `${names}: distance in mm from the run's landmark to the same skin point on the reference ` +
    `(placed once on the skin at rest, so that skin sliding along the profile counts); ${LANDMARK_FLAG_MM} mm or ` +
    "more in red.";
  return note;
}

function ratioTable(report) {
  const measured = report.patients.filter((p) => p.ratios_fine);
  const named = measured.map((p) => [p.id, p.ratios_fine]);
  if (report.real_face_ratios) named.push(["ArtiSynth face", report.real_face_ratios]);
  if (!named.length) return document.createTextNode("No ratios measured.");
  const head = ["", ...named[0][1].map((r) => r.ratio)];
  const cell = (r) => {
    if (r.value === null) return ["n/a", ""];
    const dir = r.direction === "setback" ? "set back" : "forward";
    const band = r.band ? `${r.band[0]}–${r.band[1]}` : "no band";
    const flagged = r.flag === "LOW" || r.flag === "HIGH";
    return [`${r.value.toFixed(2)} ${dir} (${band})${flagged ? " " + r.flag : ""}`, flagged ? "flag" : ""];
  };
  return reportTable(head, named.map(([id, ratios]) => [id, ...ratios.map(cell)]));
}

async function loadReport() {
  const box = document.getElementById("report-body");
  if (box.dataset.loaded) return;
  box.dataset.loaded = "1";
  box.textContent = "Loading…";
  let report;
  try {
    const response = await fetch(REPORT_JSON, { cache: "no-cache" });
    if (!response.ok) throw new Error(`${REPORT_JSON}: HTTP ${response.status}`);
    report = await response.json();
  } catch (e) {
    box.textContent = `No accuracy report on this server (${e.message}). ` +
      "Write one with: orthosim bench cohort --json web/cohort/cohort.json --image web/cohort/speed-error.png";
    delete box.dataset.loaded;
    return;
  }
  box.textContent = "";
  const intro = document.createElement("p");
  intro.className = "hint";
  intro.textContent = `Synthetic cohort of ${report.patients.length} phantom patients` +
    (report.measured_at ? `, measured ${report.measured_at}` : "") +
    ` on ${report.hardware_threads} hardware threads` +
    (report.load_average ? ` (load average ${report.load_average})` : "") +
    `; solve times are medians of ${report.repeats}. Reference: ${report.reference.what}, ` +
    `${report.reference.skin_triangles} skin triangles, tolerances ×${report.reference.tolerance_scale}.` +
    (report.contact ? "" : " Without lips–teeth contact.");
  const plot = document.createElement("img");
  plot.id = "report-plot";
  plot.alt = "solve time against face area within 1 mm of the reference";
  plot.src = REPORT_PLOT;
  const ratiosIntro = document.createElement("p");
  ratiosIntro.className = "hint";
  ratiosIntro.textContent = "Soft-to-hard movement ratios of the fine prediction beside the published bands " +
    "(forward movement over the bone's, as the studies measure them; plausibility checks, not clinical " +
    "validation); flagged values fall outside.";
  box.append(intro, tableFour(report), tableFourNote(), runNotes(report), plot, ratiosIntro, ratioTable(report));
  const stale = schemaNote(report);
  if (stale) box.prepend(stale);
}

// A report written in another format is still shown as far as it reads, under a warning.
function schemaNote(report) {
  if (report.schema_version === REPORT_SCHEMA_VERSION) return null;
  const note = document.createElement("p");
  note.id = "report-schema";
  note.className = "hint flag";
  note.textContent = `This report is in format ${report.schema_version ?? "(none: older than format 1)"}, ` +
    `this page reads format ${REPORT_SCHEMA_VERSION}: some figures may be missing or misread. Refresh it with ` +
    "orthosim bench cohort --json web/cohort/cohort.json --image web/cohort/speed-error.png";
  return note;
}

// What the table's numbers rest on: references solved differently, and the solver's warnings.
function runNotes(report) {
  const list = document.createElement("ul");
  list.className = "hint";
  for (const p of report.patients) {
    if (p.reference_note) list.append(Object.assign(document.createElement("li"), { textContent: `${p.id}: ${p.reference_note}` }));
    for (const run of ["coarse", "fine", "reference"])
      for (const w of (p[run] && p[run].warnings) || [])
        list.append(Object.assign(document.createElement("li"), { textContent: `${p.id} ${run}: ${w}` }));
  }
  return list;
}

document.getElementById("report").addEventListener("toggle", (e) => { if (e.target.open) loadReport(); });
