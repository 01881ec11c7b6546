// Browser test of "New patient": the phantom's own surfaces, written by
// `orthosim phantom`, are uploaded through the page's form; a bad file is refused with its name,
// then the good set becomes a case that opens, moving its Le Fort I maxilla gives a converged
// preview, a click on the face picks the skin; then three landmarks are placed by clicking the
// face, the Le Fort I is shifted 2 mm up and tilted 5 degrees, the case is rebuilt with its progress
// shown and previews. Runs on its own data folder, so the shared one never holds the imported patient.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdirSync, mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { artifacts, cli, waitForPage, withPage } from "./harness.mjs";

test("new patient: upload surfaces, refusal named, case opens and previews", { timeout: 400000 }, async () => {
  const work = mkdtempSync(path.join(tmpdir(), "orthosim-new-patient-"));
  try {
    const exported = path.join(work, "export");
    execFileSync(cli, ["phantom", "--out", exported, "--variant", "0"], { stdio: "ignore" });
    const file = (name) => path.join(exported, name);
    const broken = path.join(work, "broken_jaw.stl");
    writeFileSync(broken, "solid nothing\nendsolid nothing\n");
    await withPage(async (page, url) => {
      const pageErrors = [];
      page.on("pageerror", (e) => pageErrors.push(e.message));
      await page.goto(url);
      await waitForPage(page, () => document.querySelector("#case-select").options.length >= 5);
      await page.click("#new-patient summary");
      await page.fill('input[aria-label="case id"]', "jane-doe");
      await page.fill('input[aria-label="patient name"]', "Jane Doe");
      await page.setInputFiles('input[aria-label="skin file"]', file("skin.obj"));
      await page.setInputFiles('input[aria-label="skull file"]', file("skull.stl"));
      await page.setInputFiles('input[aria-label="mandible file"]', broken);
      await page.setInputFiles('input[aria-label="cavity files"]', file("oral_cavity.stl"));
      await page.setInputFiles('input[aria-label="landmarks file"]', file("landmarks.json"));

      // A damaged mandible: refused, with its file named; nothing joins the list.
      await page.click("#import-patient");
      await waitForPage(page, () => /not imported/.test(document.querySelector("#import-status").textContent), null, { timeout: 120000 });
      assert.match(await page.locator("#import-status").textContent(), /broken_jaw\.stl/);

      // The right mandible: imported, listed, opened.
      await page.setInputFiles('input[aria-label="mandible file"]', file("mandible.stl"));
      await page.click("#import-patient");
      await waitForPage(page, () => /imported Jane Doe/.test(document.querySelector("#import-status").textContent), null, { timeout: 120000 });
      assert.equal(Number(await page.locator("#import-progress").evaluate((p) => p.value)), 1);
      await waitForPage(page, () => [...document.querySelector("#case-select").options].some((o) => o.value === "jane-doe"));
      const slider = page.locator('input[aria-label="maxilla anterior_mm"]');
      await slider.waitFor({ timeout: 180000 });
      assert.equal(await page.locator("#case-select").inputValue(), "jane-doe");

      // Le Fort I 2 mm forward: a converged preview in which the upper lip follows.
      await waitForPage(page, () => /Solved in/.test(document.querySelector("#preview-figures").textContent), null, { timeout: 120000 });
      await slider.focus();
      for (let i = 0; i < 4; i++) await page.keyboard.press("ArrowRight");
      assert.equal(Number(await slider.inputValue()), 2);
      await waitForPage(page, () => {
        const rows = [...document.querySelectorAll("#preview-figures tr")];
        const lip = rows.find((r) => /upper lip/.test(r.textContent));
        return lip && Number(lip.children[1].textContent) > 0.5;
      }, null, { timeout: 120000 });
      await waitForPage(page, () => document.querySelector("#solve-state").dataset.state === "converged", null, { timeout: 120000 });
      // A click (no drag) on the face picks the skin under it.
      const box = await page.locator("#frame-box").boundingBox();
      await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
      await waitForPage(page, () => /picked skin at/.test(document.querySelector("#pick-info").textContent), null, { timeout: 30000 });

      // Three landmarks placed by clicking the face, the Le Fort I shifted 2 mm up, the case rebuilt
      // with its progress shown, then a preview on the rebuilt case.
      assert.equal(await page.locator("#case-editor").isHidden(), false, "an imported patient is editable");
      // The frame is shown with where it comes from (the phantom has no porions: the files' axes),
      // and the landmarks the cuts need are listed with the cut that needs them.
      assert.match(await page.locator("#frame-status").textContent(), /anterior \(-1\.00, 0\.00, 0\.00\).*files' axes/);
      const apexRow = await page.locator("#landmark-table tr", { hasText: "upper_incisor_apex" }).first().textContent();
      assert.match(apexRow, /le_fort_1/);
      assert.ok(await page.locator("#landmark-table tr.missing", { hasText: "porion_left" }).count() === 1, "porion_left not placed");
      const clicks = [["pronasale", 0], ["subnasale", 12], ["labrale_superius", 24]];
      for (const [name, dy] of clicks) {
        await page.click(`#landmark-table button[data-landmark="${name}"]`);
        await page.locator("#frame-box").scrollIntoViewIfNeeded();  // clicking the button may scroll the page
        const at = await page.locator("#frame-box").boundingBox();
        await page.mouse.click(at.x + at.width / 2, at.y + at.height / 2 + dy);
        await waitForPage(page, (n) => [...document.querySelectorAll("#landmark-table tr")]
          .some((r) => r.textContent.startsWith(`${n} (new place)`)), name, { timeout: 30000 })
          .catch(async (e) => {
            console.log("edit-status:", await page.locator("#edit-status").textContent(), "| pick-info:",
              await page.locator("#pick-info").textContent(), "| messages:", await page.locator("#messages").textContent());
            throw e;
          });
      }
      const offset = page.locator('input[aria-label="le_fort_1 offset"]');
      assert.equal(Number(await offset.inputValue()), 4, "the Le Fort I at its default level");
      await offset.fill("6");
      await page.fill('input[aria-label="le_fort_1 tilt"]', "5");
      const progressSeen = waitForPage(page, () => !document.querySelector("#rebuild-progress").hidden, null, { timeout: 60000 });
      await page.click("#apply-edit");
      await progressSeen;
      await waitForPage(page, () => /case rebuilt/.test(document.querySelector("#edit-status").textContent), null, { timeout: 180000 });
      assert.equal(Number(await offset.inputValue()), 6, "the rebuilt case has the shifted Le Fort I");
      assert.equal(Number(await page.locator('input[aria-label="le_fort_1 tilt"]').inputValue()), 5, "and tilted");
      assert.equal(await page.locator("#landmark-table").textContent().then((t) => /new place/.test(t)), false);
      await slider.waitFor({ timeout: 60000 });
      await slider.focus();
      for (let i = 0; i < 2; i++) await page.keyboard.press("ArrowRight");
      await waitForPage(page, () => document.querySelector("#solve-state").dataset.state === "converged" &&
        /upper lip/.test(document.querySelector("#preview-figures").textContent), null, { timeout: 120000 });
      mkdirSync(artifacts, { recursive: true });
      await page.screenshot({ path: path.join(artifacts, "new-patient.png"), fullPage: true });
      assert.deepEqual(pageErrors, [], "no script errors on the page");
    }, { dataDir: path.join(work, "data") });
  } finally {
    rmSync(work, { recursive: true, force: true });
  }
});
