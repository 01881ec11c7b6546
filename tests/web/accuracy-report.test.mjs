// Browser test of the accuracy report on the planning page (issue 7): opening it shows the
// committed cohort report (web/cohort/) as the paper's Table 4, the speed-versus-error plot and
// the soft-to-hard ratios, with exactly the flags the report counts. It checks the page against
// that committed SNAPSHOT of `orthosim bench cohort`, not against a fresh run (20+ min): that the
// snapshot is in the bench's current format is checked by its schema_version here (against the
// page's reader) and in C++ (CohortReportSchema: against the writer's constant; CohortBench: its
// fields against a fresh small run).
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { withPage } from "./harness.mjs";

const report = JSON.parse(readFileSync(new URL("../../web/cohort/cohort.json", import.meta.url)));

test("accuracy report from the committed web/cohort snapshot: Table 4, plot and flagged ratios", { timeout: 120000 }, async () => {
  await withPage(async (page, url) => {
    const pageErrors = [];
    page.on("pageerror", (e) => pageErrors.push(e.message));
    await page.goto(url);
    assert.equal(await page.locator("#report-body table").count(), 0, "nothing loaded before the report is opened");
    await page.click("#report summary");
    await page.waitForFunction(() => document.querySelectorAll("#report-body table").length === 2, null, { timeout: 30000 });
    // The snapshot is in the format the page reads: no stale-report warning.
    assert.equal(report.schema_version, await page.evaluate(() => REPORT_SCHEMA_VERSION), "web/cohort/cohort.json schema_version");
    assert.equal(await page.locator("#report-schema").count(), 0, "no stale-report warning");

    // Table 4: one row per patient, the share within 3 mm as the bench measured it.
    const rows = await page.locator("#report-body table").first().locator("tbody tr").allTextContents();
    assert.equal(rows.length, report.patients.length);
    report.patients.forEach((p, i) => {
      assert.ok(rows[i].startsWith(p.id), `row ${i} is ${p.id}`);
      if (p.error) assert.match(rows[i], /not measured/);
      else assert.ok(rows[i].includes(`${(100 * p.fine.face_region.share_within[2]).toFixed(1)} %`), rows[i]);
    });

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
