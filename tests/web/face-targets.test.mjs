// Browser test of planning from the face: open the phantom, tick the chin and the
// upper lip, type their targets, find poses; the server's iterations are shown, the sliders move
// to the poses found, the misses are listed and a converged preview of those poses follows.
// Environment as harness.mjs says.
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync } from "node:fs";
import path from "node:path";
import { artifacts, waitForPage, withPage } from "./harness.mjs";

test("plan from the face: typed targets move the sliders, a converged preview follows", { timeout: 300000 }, async () => {
  await withPage(async (page, url) => {
    const pageErrors = [];
    page.on("pageerror", (e) => pageErrors.push(e.message));
    const received = [];
    page.on("websocket", (ws) => ws.on("framereceived", (f) => {
      if (typeof f.payload === "string") received.push(JSON.parse(f.payload));
    }));
    await page.goto(url);
    await waitForPage(page, () => document.querySelector("#case-select").options.length >= 1);
    await page.selectOption("#case-select", "phantom-0");
    await page.click("#open-case");
    await page.locator('input[aria-label="target soft_pogonion"]').waitFor({ timeout: 120000 });
    await waitForPage(page, () => /Solved in/.test(document.querySelector("#preview-figures").textContent), null, { timeout: 60000 });
    assert.ok(await page.locator('input[aria-label="lock ramus_left anterior_mm"]').isChecked(), "the rami start locked");

    // Chin 3 mm forward, upper lip 1.5 mm forward; the maxilla keeps its height (locked).
    await page.check('input[aria-label="target soft_pogonion"]');
    await page.fill('input[aria-label="soft_pogonion target forward"]', "3");
    await page.check('input[aria-label="target labrale_superius"]');
    await page.fill('input[aria-label="labrale_superius target forward"]', "1.5");
    await page.check('input[aria-label="lock maxilla superior_mm"]');
    const slider = page.locator('input[aria-label="mandible anterior_mm"]');
    assert.equal(Number(await slider.inputValue()), 0);
    await page.click("#find-poses");

    await waitForPage(page, () => /every target reached|cannot be reached/.test(document.querySelector("#face-status").textContent), null, { timeout: 120000 });
    const status = await page.locator("#face-status").textContent();
    assert.match(status, /every target reached/, status);
    assert.ok(received.some((m) => m.type === "face_progress"), "the iterations were reported");
    const plan = received.find((m) => m.type === "face_plan");
    assert.equal(plan.poses.maxilla.superior_mm, 0, "the locked value stayed");
    // The sliders show the poses found.
    assert.ok(Math.abs(Number(await slider.inputValue()) - plan.poses.mandible.anterior_mm) <= 0.25,
      `slider ${await slider.inputValue()} vs ${plan.poses.mandible.anterior_mm}`);
    assert.ok(plan.poses.mandible.anterior_mm > 1, JSON.stringify(plan.poses.mandible));
    const miss = await page.locator('td[data-miss="soft_pogonion"]').textContent();
    assert.match(miss, /^0\.\d\d mm$/);
    // A converged preview of those poses follows, and the chin is where it was asked to be.
    const by = Date.now() + 60000;
    while (!received.slice().reverse().find((m) => m.type === "preview" && m.poses.mandible.anterior_mm === plan.poses.mandible.anterior_mm) && Date.now() < by)
      await page.waitForTimeout(100);
    const preview = received.slice().reverse().find((m) => m.type === "preview" && m.poses.mandible.anterior_mm === plan.poses.mandible.anterior_mm);
    assert.ok(preview && preview.figures.converged, "a converged preview of the poses found");
    assert.ok(Math.abs(preview.figures.landmarks.soft_pogonion.anterior_mm - 3) < 0.25, JSON.stringify(preview.figures.landmarks.soft_pogonion));
    await waitForPage(page, () => /Solved in/.test(document.querySelector("#preview-figures").textContent));

    mkdirSync(artifacts, { recursive: true });
    await page.screenshot({ path: path.join(artifacts, "face-targets.png"), fullPage: true });
    assert.deepEqual(pageErrors, []);
  });
});
