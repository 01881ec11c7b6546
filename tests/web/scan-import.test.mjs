// Browser test of "New patient" from a CT scan: the phantom's CT, written as a DICOM series by
// `orthosim phantom --ct`, is sent as a folder from the page; the preview shows three slices with
// the thresholds the server chose, moving the bone slider redraws them, a click on a slice at the
// mandible's seed seeds it there, and "Import" makes the case, shows the scan's report with the suggested
// landmarks and opens it. Runs on its own data folder.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdirSync, mkdtempSync, readdirSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { artifacts, cli, waitForPage, withPage } from "./harness.mjs";

test("scan import: stage a CT folder, preview, change the bone threshold, import", { timeout: 500000 }, async () => {
  const work = mkdtempSync(path.join(tmpdir(), "orthosim-scan-import-"));
  try {
    const ct = path.join(work, "ct");
    execFileSync(cli, ["phantom", "--out", path.join(work, "phantom"), "--ct", ct, "--ct-spacing", "1"],
      { stdio: "ignore" });
    assert.ok(readdirSync(ct).length > 100, "the CT series was written");
    await withPage(async (page, url) => {
      const pageErrors = [];
      page.on("pageerror", (e) => pageErrors.push(e.message));
      await page.goto(url);
      await waitForPage(page, () => document.querySelector("#case-select").options.length >= 1);
      await page.click("#new-patient summary");
      await page.setInputFiles("#scan-folder", ct);
      await page.click("#stage-scan");

      // Three slices, the thresholds the server used on the sliders (Hounsfield defaults).
      await waitForPage(page, () => document.querySelectorAll("#scan-images img").length === 3, null, { timeout: 180000 })
        .catch(async (e) => { console.log("scan-status:", await page.locator("#scan-status").textContent()); throw e; });
      assert.equal(Number(await page.locator("#scan-bone").inputValue()), 300);
      assert.equal(Number(await page.locator("#scan-skin").inputValue()), -400);
      const planes = await page.locator("#scan-images img").evaluateAll((imgs) => imgs.map((i) => i.dataset.plane));
      assert.deepEqual(planes, ["axial", "sagittal", "coronal"]);
      assert.match(await page.locator("#scan-notes").textContent(), /thresholds from/);
      const before = await page.locator('#scan-images img[data-plane="coronal"]').getAttribute("src");

      // The bone slider moved: the preview is asked again and the slices change.
      await page.locator("#scan-bone").evaluate((s) => {
        s.value = "700";
        s.dispatchEvent(new Event("input", { bubbles: true }));
      });
      await waitForPage(page, (old) => {
        const img = document.querySelector('#scan-images img[data-plane="coronal"]');
        return img && img.src !== old;
      }, before, { timeout: 120000 });
      assert.match(await page.locator("#scan-status").textContent(), /bone 700/);

      // Back to the default, then a click on the sagittal slice's chin seeds the mandible there.
      await page.locator("#scan-bone").evaluate((s) => {
        s.value = "300";
        s.dispatchEvent(new Event("input", { bubbles: true }));
      });
      await waitForPage(page, () => /bone 300/.test(document.querySelector("#scan-status").textContent), null, { timeout: 120000 });
      const marker = page.locator(".scan-slice .seed.mandible").first();
      assert.ok(await page.locator(".scan-slice .seed.mandible").count() >= 1, "the mandible's seed is shown");
      await marker.scrollIntoViewIfNeeded();
      const at = await marker.boundingBox();
      await page.mouse.click(at.x + at.width / 2, at.y + at.height / 2);  // the seed lets the click through
      await waitForPage(page, () => /mandible seed at/.test(document.querySelector("#scan-status").textContent), null, { timeout: 10000 });
      await waitForPage(page, () => /segmented with/.test(document.querySelector("#scan-status").textContent), null, { timeout: 120000 });

      await page.fill('input[aria-label="scan case id"]', "ct-jane");
      await page.fill('input[aria-label="scan patient name"]', "CT Jane");
      await page.click("#import-scan");
      assert.equal(await page.locator("#scan-working").isHidden(), false, "the import says it is working");
      // The stage the server reports, not only the time: the import makes and checks surfaces for seconds.
      await waitForPage(page, () => /making the surfaces|checking and repairing|placing the landmarks|writing the case/
        .test(document.querySelector("#scan-working").textContent), null, { timeout: 120000 });
      await waitForPage(page, () => /Suggested landmarks/.test(document.querySelector("#scan-report").textContent), null, { timeout: 300000 })
        .catch(async (e) => { console.log("scan-status:", await page.locator("#scan-status").textContent()); throw e; });
      const report = await page.locator("#scan-report").textContent();
      assert.match(report, /Scan:/);
      assert.match(report, /CT/);
      await waitForPage(page, () => [...document.querySelector("#case-select").options].some((o) => o.value === "ct-jane"), null, { timeout: 60000 });
      mkdirSync(artifacts, { recursive: true });
      await page.screenshot({ path: path.join(artifacts, "scan-import.png"), fullPage: true });
      assert.deepEqual(pageErrors, [], "no script errors on the page");
    }, { dataDir: path.join(work, "data") });
  } finally {
    rmSync(work, { recursive: true, force: true });
  }
});
