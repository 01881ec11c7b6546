// The accuracy report: the last `orthosim bench cohort` run written into web/cohort/ (its JSON
// and speed-versus-error plot), shown as the paper's Table 4 and the soft-to-hard ratios with
// their plausibility flags. Loaded only when the clinician opens the report.
"use strict";

const REPORT_JSON = "cohort/cohort.json";
const REPORT_PLOT = "cohort/speed-error.png";
// The report format this page reads: the bench's kCohortReportSchemaVersion (engine/eval/CohortJson.hpp).
const REPORT_SCHEMA_VERSION = 1;

function reportCell(row, text, className) {
  const cell = document.createElement(row.parentElement && row.parentElement.tagName === "THEAD" ? "th" : "td");
  cell.textContent = text;
  if (className) cell.className = className;
  row.append(cell);
  return cell;
}

function reportTable(head, rows) {
  const table = document.createElement("table");
  const thead = table.createTHead();
  const hr = thead.insertRow();
  head.forEach((h) => reportCell(hr, h));
  const body = table.createTBody();
  rows.forEach((r) => {
    const tr = body.insertRow();
    r.forEach((c) => (Array.isArray(c) ? reportCell(tr, c[0], c[1]) : reportCell(tr, c)));
  });
  return table;
}

const pct = (share) => (share === undefined ? "—" : `${(100 * share).toFixed(1)} %`);
const secs = (s) => (s === undefined ? "—" : s.toFixed(2));

function tableFour(report) {
  const rows = report.patients.map((p) => {
    if (p.error) return [p.id, p.procedure, ["not measured: " + p.error, "flag"], "", "", "", "", ""];
    const c = p.coarse, f = p.fine;
    return [p.id, `${p.diagnosis}: ${p.procedure}`, c.skin_triangles, secs(c.solve_s), pct(c.face_region.share_within[2]),
      f.skin_triangles, secs(f.solve_s), pct(f.face_region.share_within[2])];
  });
  return reportTable(["patient", "procedure", "coarse triangles", "solve s", "within 3 mm",
    "fine triangles", "solve s", "within 3 mm"], rows);
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
  box.append(intro, tableFour(report), runNotes(report), plot, ratiosIntro, ratioTable(report));
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
