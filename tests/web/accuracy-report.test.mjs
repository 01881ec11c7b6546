// Browser test of the accuracy report on the planning page: opening it shows the
// committed cohort report (web/cohort/) as the paper's Table 4 (with the lips and soft pogonion),
// the speed-versus-error plot and the soft-to-hard ratios, with exactly the flags the
// report counts. It checks the page against
// that committed SNAPSHOT of `orthosim bench cohort`, not against a fresh run (20+ min): that the
// snapshot is in the bench's current format is checked by its schema_version here (against the
// page's reader) and in C++ (CohortReportSchema: against the writer's constant; CohortBench: its
// fields against a fresh small run).
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { waitForPage, withPage } from "./harness.mjs";

const report = JSON.parse(readFileSync(new URL("../../web/cohort/cohort.json", import.meta.url)));

test("accuracy report from the committed web/cohort snapshot: Table 4 with the lips and soft pogonion, plot and flagged ratios", { timeout: 120000 }, async () => {
  await withPage(async (page, url) => {
    const pageErrors = [];
    page.on("pageerror", (e) => pageErrors.push(e.message));
    await page.goto(url);
    assert.equal(await page.locator("#report-body table").count(), 0, "nothing loaded before the report is opened");
    await page.click("#report summary");
    await waitForPage(page, () => document.querySelectorAll("#report-body table").length === 2, null, { timeout: 30000 });
    // The snapshot is in the format the page reads: no stale-report warning.
    assert.equal(report.schema_version, await page.evaluate(() => REPORT_SCHEMA_VERSION), "web/cohort/cohort.json schema_version");
    assert.equal(await page.locator("#report-schema").count(), 0, "no stale-report warning");

    // Table 4: one row per patient; for coarse and fine, the shares within 1 and 3 mm and the
    // distance at the lips and soft pogonion as the bench measured them, in the columns their
    // headers name.
    const table = page.locator("#report-body table").first();
    const head = await table.locator("thead tr").last().locator("th").allTextContents();
    const landmarks = [{ name: "labrale_inferius", label: "Li" }, { name: "labrale_superius", label: "Ls" },
      { name: "soft_pogonion", label: "Pog'" }];
    const runHead = ["triangles", "solve s", "≤1 mm", "≤3 mm", ...landmarks.map((l) => l.label)];
    assert.deepEqual(head, ["patient", "procedure", ...runHead, ...runHead]);
    const groups = await table.locator("thead tr").first().locator("th").allTextContents();
    assert.deepEqual(groups, ["", "coarse", "fine"]);
    const rows = await table.locator("tbody tr").all();
    assert.equal(rows.length, report.patients.length);
    const pctText = (share) => `${(100 * share).toFixed(1)} %`;
    let flaggedLandmarks = 0;
    for (const [i, p] of report.patients.entries()) {
      const cells = await rows[i].locator("td").allTextContents();
      assert.equal(cells[0], p.id, `row ${i}`);
      assert.equal(cells.length, head.length, `row ${i} has a cell per column`);
      if (p.error) {
        assert.match(cells[2], /not measured/);
        continue;
      }
      ["coarse", "fine"].forEach((run, k) => {
        const col = (name) => cells[head.indexOf(name, 2 + k * runHead.length)];
        const r = p[run];
        assert.equal(col("≤1 mm"), pctText(r.face_region.share_within[0]), `${p.id} ${run} within 1 mm`);
        assert.equal(col("≤3 mm"), pctText(r.face_region.share_within[2]), `${p.id} ${run} within 3 mm`);
        for (const l of landmarks) {
          const d = r.landmark_error_mm[l.name];
          assert.equal(typeof d, "number", `${p.id} ${run} ${l.name} measured in the snapshot`);
          assert.equal(col(l.label), d.toFixed(2), `${p.id} ${run} ${l.name}`);
          if (d >= 1) ++flaggedLandmarks;
        }
      });
    }
    // Landmarks 1 mm or more from the reference are marked, and only those.
    assert.equal(await table.locator("td.flag").count(),
      flaggedLandmarks + report.patients.filter((p) => p.error).length);
    // What the columns measure.
    assert.match(await page.locator("#report-table4-note").textContent(), /same skin point on the reference/);

    // The plot is the bench's image, loaded.
    const size = await page.locator("#report-plot").evaluate(async (img) => {
      await img.decode();
      return [img.naturalWidth, img.naturalHeight];
    });
    assert.ok(size[0] > 200 && size[1] > 150, `plot ${size}`);

    // Every ratio outside its band is flagged, and nothing else.
    const flagged = await page.locator("#report-body table").nth(1).locator("td.flag").count();
    assert.equal(flagged, report.ratios_outside_band);
    assert.deepEqual(pageErrors, [], "no script errors on the page");
  });
});

test("a report in another format is shown under a warning", { timeout: 120000 }, async () => {
  await withPage(async (page, url) => {
    const stale = { ...report };
    delete stale.schema_version;  // as written before the bench had one
    await page.route("**/cohort/cohort.json", (route) => route.fulfill({ json: stale }));
    await page.goto(url);
    await page.click("#report summary");
    await page.waitForSelector("#report-schema", { timeout: 30000 });
    assert.match(await page.locator("#report-schema").textContent(), /orthosim bench cohort/);
    assert.equal(await page.locator("#report-body table").count(), 2, "still shown as far as it reads");
  });
});
