// Browser test of the accuracy report on the planning page (issue 7): opening it shows the
// committed cohort report (web/cohort/) as the paper's Table 4, the speed-versus-error plot and
// the soft-to-hard ratios, with exactly the flags the report counts.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { withPage } from "./harness.mjs";

const report = JSON.parse(readFileSync(new URL("../../web/cohort/cohort.json", import.meta.url)));

test("accuracy report: Table 4, plot and flagged ratios", { timeout: 120000 }, async () => {
  await withPage(async (page, url) => {
    const pageErrors = [];
    page.on("pageerror", (e) => pageErrors.push(e.message));
    await page.goto(url);
    assert.equal(await page.locator("#report-body table").count(), 0, "nothing loaded before the report is opened");
    await page.click("#report summary");
    await page.waitForFunction(() => document.querySelectorAll("#report-body table").length === 2, null, { timeout: 30000 });

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
