// The prediction band (docs/protocol.md, "Prediction band"): runs a band job of the current poses,
// shows its progress (which solve of how many), then the band's width as the "band" colour map,
// the landmark ranges as a table, buttons that flip the drawn face between the low and high
// envelopes, and the envelopes' export. Band jobs share the fine jobs' messages; their `kind` is
// "band", so the fine job's box is left alone. A band is of the poses it was run with: once the
// preview shows other poses it says so, until the poses are back or a new band is run.
"use strict";

const band = { job: null, done: null };

function bandJobMessage(type, m) {
  const p = $("band-progress");
  if (type === "job_queued") {
    band.job = m.job;
    p.hidden = false;
    p.value = 0;
    $("band-cancel").disabled = false;
    $("band-status").textContent = `Band job ${m.job}: ${m.solves} solves at ${m.resolution} resolution, queued (${m.position} ahead)`;
  } else if (type === "job_progress") {
    p.hidden = false;
    p.value = m.fraction;
    $("band-status").textContent = m.phase === "solve"
      ? `Band job ${m.job}: solve ${m.solve} of ${m.solves} (${m.run}), ${Math.round(m.fraction * 100)}%`
      : `Band job ${m.job}: ${m.phase}…`;
  } else {
    p.hidden = true;
    $("band-cancel").disabled = true;
    $("band-status").textContent = `Band job ${m.job}: ${type === "job_cancelled" ? "cancelled" : m.message}`;
  }
}

const fmt = (x) => (x >= 0 ? "+" : "") + x.toFixed(2);

function onBandDone(m) {
  band.done = m;
  $("band-progress").hidden = true;
  $("band-cancel").disabled = true;
  const b = m.band;
  const failed = b.runs.filter((r) => !r.converged);
  const stale = element("b", "", "This band is of earlier poses: run it again for the current plan.");
  stale.id = "band-stale";
  stale.hidden = true;
  $("band-status").replaceChildren(
    `Band job ${m.job} done: ${b.converged} of ${b.solves} solves converged in ` +
    `${m.time_s.toFixed(1)} s (${m.resolution}). Band width up to `, element("b", "", `${b.width.max_mm.toFixed(2)} mm`),
    `; ${(b.width.share_over_1mm * 100).toFixed(1)}% of the skin over 1 mm.` +
    (failed.length ? ` Left out (did not converge): ${failed.map((r) => r.label).join(", ")}.` : "") + " ", stale);
  const cell = (tag, text) => { const c = document.createElement(tag); c.textContent = text; return c; };
  const rows = [];
  for (const l of b.landmarks) {
    if (!l.measured) continue;
    const range = (axis) => `${fmt(l.low_mm[axis])} … ${fmt(l.high_mm[axis])}`;
    // The parameter that moves this landmark most (one at a time).
    let most = "", best = -1;
    for (const s of b.sensitivity) {
      const e = s.effect_mm[l.name];
      if (e && e.magnitude > best) { best = e.magnitude; most = s.parameter; }
    }
    // Names as text, never markup: landmark names come from users' files.
    const row = document.createElement("tr");
    row.dataset.landmark = l.name;
    row.append(cell("td", LANDMARK_NAMES[l.name] || l.name), cell("td", range("anterior")),
      cell("td", range("superior")), cell("td", range("right")), cell("td", `${most} (${best.toFixed(2)})`));
    rows.push(row);
  }
  const head = document.createElement("tr");
  for (const h of ["landmark (mm about nominal)", "forward", "up", "right", "moved most by"]) head.append(cell("th", h));
  $("band-table").replaceChildren(head, ...rows);
  $("band-flip").hidden = !m.view;
  $("band-export-row").hidden = false;
  if (m.view) {
    $("colormap").value = "band";
    sendView({ colormap: "band" });
  }
}

function setupBand() {
  for (const t of ["job_queued", "job_progress", "job_cancelled", "job_failed"]) {
    const fine = handlers[t];
    handlers[t] = (m) => (m.kind === "band" ? bandJobMessage(t, m) : fine(m));
  }
  handlers.band_done = onBandDone;
  const preview = handlers.preview;
  handlers.preview = (m) => {
    preview(m);
    const stale = $("band-stale");
    if (band.done && stale) stale.hidden = JSON.stringify(m.poses) === JSON.stringify(band.done.poses);
  };
  handlers.band_view = (m) => {
    for (const b of document.querySelectorAll("#band-flip button")) b.classList.toggle("active", b.dataset.band === m.surface);
    $("band-flip").dataset.shown = m.surface;
  };
  const exported = handlers.exported;
  handlers.exported = (m) => {
    if (!m.result.startsWith("band_")) return exported(m);
    const a = $("band-download");
    a.href = m.url + (token() ? "?token=" + encodeURIComponent(token()) : "");
    a.download = m.file_name;
    a.textContent = `download ${m.file_name} (${(m.bytes / 1e6).toFixed(1)} MB)`;
    a.hidden = false;
  };
  const opened = handlers.opened;
  handlers.opened = (m) => {
    opened(m);
    band.done = null;
    $("band-run").disabled = false;
    $("band-flip").hidden = true;
    $("band-export-row").hidden = true;
    $("band-table").replaceChildren();
    $("band-status").textContent = "";
  };
  $("band-run").onclick = () => send({ type: "band", resolution: $("band-resolution").value });
  $("band-cancel").onclick = () => band.job && send({ type: "cancel", job: band.job });
  for (const b of document.querySelectorAll("#band-flip button"))
    b.onclick = () => send({ type: "band_view", surface: b.dataset.band });
  $("band-export").onclick = () =>
    send({ type: "export_band", surface: $("band-export-surface").value, format: $("band-export-format").value });
}

setupBand();
