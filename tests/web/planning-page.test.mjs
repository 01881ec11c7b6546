// Browser test of the planning page: Debian's Chromium, headless, driven by
// playwright-core, against a real `orthosim serve` started here. Opens the phantom, moves the
// maxilla advancement slider (0.5 mm steps), sees a new frame, a solve time and the converged state, confirms on the fine model to
// 100 %, and saves a screenshot as a test artefact.
// Environment: ORTHOSIM_CLI (the executable), ORTHOSIM_TEST_DATA (server data folder),
// ARTIFACT_DIR (where the screenshot goes); see harness.mjs.
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync, statSync } from "node:fs";
import path from "node:path";
import { artifacts, waitForPage, withPage } from "./harness.mjs";

test("planning page: slider preview, fine confirm, screenshot", { timeout: 300000 }, async () => {
  await withPage(async (page, url) => {
    const pageErrors = [];
    page.on("pageerror", (e) => pageErrors.push(e.message));
    // What goes over the session's WebSocket: the poses sent, the server's drag readiness and the
    // faces its frames say they show.
    const sentPoses = [];
    const frames = [];
    let dragReady = false;
    page.on("websocket", (ws) => {
      ws.on("framesent", (f) => { if (typeof f.payload === "string" && /"set_poses"/.test(f.payload)) sentPoses.push(JSON.parse(f.payload)); });
      ws.on("framereceived", (f) => {
        if (typeof f.payload !== "string") return;
        const m = JSON.parse(f.payload);
        if (m.type === "drag_ready") dragReady = true;
        if (m.type === "frame") frames.push(m.shows);
      });
    });
    await page.goto(url);
    await waitForPage(page, () => document.querySelector("#case-select").options.length >= 5);
    await page.selectOption("#case-select", "phantom-0");
    await page.click("#open-case");

    // The face arrives as a streamed frame, then the preview of the rest pose.
    const slider = page.locator('input[aria-label="maxilla anterior_mm"]');
    await slider.waitFor({ timeout: 120000 });
    await waitForPage(page, () => document.querySelector("#frame").src.startsWith("blob:"), null, { timeout: 60000 });
    await waitForPage(page, () => /Solved in/.test(document.querySelector("#preview-figures").textContent), null, { timeout: 60000 });
    const before = await page.locator("#frame").getAttribute("src");

    // Drag-like input: 8 key presses of 0.5 mm move the maxilla 4 mm forward; the number field
    // follows, and its arrow keys step 0.5 mm too. The poses go out while the slider moves (the
    // first at once, then at most every 50 ms), each drawn at once from the linear response.
    const readyBy = Date.now() + 60000;
    while (!dragReady && Date.now() < readyBy) await page.waitForTimeout(100);
    assert.ok(dragReady, "the server built the drag response of the rest preview");
    await slider.focus();
    for (let i = 0; i < 8; i++) await page.keyboard.press("ArrowRight");
    assert.equal(Number(await slider.inputValue()), 4);
    const number = page.locator('label.axis:has(input[aria-label="maxilla anterior_mm"]) input[type="number"]');
    assert.equal(Number(await number.inputValue()), 4);
    assert.equal(await number.getAttribute("step"), "0.5");
    await waitForPage(page, 
      (old) => document.querySelector("#frame").src !== old &&
        /upper lip/.test(document.querySelector("#preview-figures").textContent), before, { timeout: 60000 });
    // The newest pose is the one shown once the previews catch up.
    await waitForPage(page, () => {
      const rows = [...document.querySelectorAll("#preview-figures tr")];
      const lip = rows.find((r) => /upper lip/.test(r.textContent));
      return lip && Number(lip.children[1].textContent) > 2.0;
    }, null, { timeout: 60000 });
    const solve = await page.locator("#solve-time").textContent();
    assert.match(solve, /Solved in \d+\.\d+ s/);
    assert.ok(sentPoses.length >= 2 && sentPoses.length <= 8, `poses sent while dragging: ${sentPoses.length}`);
    assert.equal(sentPoses.at(-1).poses.maxilla.anterior_mm, 4, "the last pose sent is the slider's");
    assert.ok(frames.some((f) => f && f.state === "linear" && sentPoses.some((p) => p.id === f.pose_id)),
      `a frame drew a dragged pose linearly: ${JSON.stringify(frames)}`);
    // The face shown is the converged one once the previews caught up; the frame rate is shown.
    await waitForPage(page, () => document.querySelector("#solve-state").dataset.state === "converged", null, { timeout: 60000 });
    assert.match(await page.locator("#solve-state").textContent(), /converged \(last solve \d+\.\d+ s/);
    assert.match(await page.locator("#frame-info").textContent(), /\d+ fps/);

    // View buttons and mouse orbit redraw the face.
    await page.click('#views button[data-view="profile"]');
    await waitForPage(page, () => /profile view/.test(document.querySelector("#frame-info").textContent), null, { timeout: 30000 });
    const profile = await page.locator("#frame").getAttribute("src");
    const box = await page.locator("#frame-box").boundingBox();
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2, { steps: 6 });
    await page.mouse.up();
    await waitForPage(page, (old) => document.querySelector("#frame").src !== old, profile, { timeout: 30000 });

    // Fine confirm to 100 %.
    await page.click("#confirm");
    await waitForPage(page, () => /done/.test(document.querySelector("#job-status").textContent), null, { timeout: 240000 });
    assert.equal(Number(await page.locator("#job-progress").evaluate((p) => p.value)), 1);
    assert.match(await page.locator("#job-status").textContent(), /Coarse vs fine on the skin/);
    await waitForPage(page, () => /difference/.test(document.querySelector("#frame-info").textContent), null, { timeout: 30000 })
      .catch(async (e) => { console.log("frame-info:", await page.locator("#frame-info").textContent(), await page.locator("#messages").textContent()); throw e; });

    mkdirSync(artifacts, { recursive: true });
    const shot = path.join(artifacts, "planning-page.png");
    await page.screenshot({ path: shot, fullPage: true });
    assert.ok(statSync(shot).size > 20000, "the screenshot shows the page");
    assert.deepEqual(pageErrors, [], "no script errors on the page");
  });
});
