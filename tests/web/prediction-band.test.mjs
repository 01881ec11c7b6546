// Browser test of the prediction band: opens the phantom, advances the maxilla
// 4 mm, runs a coarse band from the page, sees its progress, the band-width colour map and the
// landmark table, flips the drawn face between the low and high envelopes, and exports the high
// envelope. Leaves a screenshot in ARTIFACT_DIR. Environment as in harness.mjs.
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync } from "node:fs";
import path from "node:path";
import { artifacts, waitForPage, withPage } from "./harness.mjs";

test("prediction band: run, colour map, landmark ranges, flip extremes, export", { timeout: 420000 }, async () => {
  await withPage(async (page, url) => {
    const pageErrors = [];
    page.on("pageerror", (e) => pageErrors.push(e.message));
    const frames = [];
    let progress = 0;
    page.on("websocket", (ws) => {
      ws.on("framereceived", (f) => {
        if (typeof f.payload !== "string") return;
        const m = JSON.parse(f.payload);
        if (m.type === "frame") frames.push(m);
        if (m.type === "job_progress" && m.kind === "band") progress++;
      });
    });
    await page.goto(url);
    await waitForPage(page, () => document.querySelector("#case-select").options.length >= 5);
    await page.selectOption("#case-select", "phantom-0");
    await page.click("#open-case");
    const slider = page.locator('input[aria-label="maxilla anterior_mm"]');
    await slider.waitFor({ timeout: 120000 });
    await waitForPage(page, () => /Solved in/.test(document.querySelector("#preview-figures").textContent), null, { timeout: 60000 });
    await slider.focus();
    for (let i = 0; i < 8; i++) await page.keyboard.press("ArrowRight");
    await waitForPage(page, () => document.querySelector("#solve-state").dataset.state === "converged", null, { timeout: 60000 });

    // The band, with its progress per solve.
    assert.equal(await page.locator("#band-run").isDisabled(), false);
    await page.selectOption("#band-resolution", "coarse");
    await page.click("#band-run");
    await waitForPage(page, () => /solve \d+ of \d+/.test(document.querySelector("#band-status").textContent), null, { timeout: 60000 });
    await waitForPage(page, () => /done: \d+ of \d+ solves converged/.test(document.querySelector("#band-status").textContent),
      null, { timeout: 300000 });
    assert.ok(progress >= 16, `progress reported per solve: ${progress} messages`);
    const status = await page.locator("#band-status").textContent();
    assert.match(status, /Band width up to \d+\.\d+ mm/);

    // The landmark ranges: the upper lip's forward range holds the nominal 0.
    const lip = page.locator('#band-table tr[data-landmark="labrale_superius"]');
    await lip.waitFor();
    const forward = (await lip.locator("td").nth(1).textContent()).split("…").map(Number);
    assert.ok(forward[0] <= 0 && forward[1] >= 0, `upper lip forward range ${forward}`);
    assert.ok(forward[1] - forward[0] > 0.05, `the band has width at the upper lip: ${forward}`);

    // The colour map switches to the band's width.
    assert.equal(await page.locator("#colormap").inputValue(), "band");
    await waitForPage(page, () => /colour map: band/.test(document.querySelector("#frame-info").textContent), null, { timeout: 60000 });

    // Flip between the extremes: the frames say which skin they draw, and the images differ.
    await page.click('#band-flip button[data-band="high"]');
    await waitForPage(page, () => document.querySelector("#solve-state").dataset.state === "band_high", null, { timeout: 60000 });
    const high = await page.locator("#frame").getAttribute("src");
    await page.click('#band-flip button[data-band="low"]');
    await waitForPage(page, () => document.querySelector("#solve-state").dataset.state === "band_low", null, { timeout: 60000 });
    assert.notEqual(await page.locator("#frame").getAttribute("src"), high);
    assert.ok(frames.some((f) => f.shows && f.shows.state === "band_high") && frames.some((f) => f.shows && f.shows.state === "band_low"));
    await page.click('#band-flip button[data-band="off"]');
    await waitForPage(page, () => document.querySelector("#solve-state").dataset.state === "converged", null, { timeout: 60000 });

    // The high envelope as a file.
    await page.selectOption("#band-export-surface", "high");
    await page.click("#band-export");
    await waitForPage(page, () => !document.querySelector("#band-download").hidden, null, { timeout: 60000 });
    assert.match(await page.locator("#band-download").textContent(), /band-high-coarse\.ply/);

    // Other poses: the band says it is of the earlier ones; back to them, it does not.
    assert.ok(await page.locator("#band-stale").isHidden());
    await slider.focus();
    await page.keyboard.press("ArrowRight");
    await waitForPage(page, () => !document.querySelector("#band-stale").hidden, null, { timeout: 60000 });
    await page.keyboard.press("ArrowLeft");
    await waitForPage(page, () => document.querySelector("#band-stale").hidden, null, { timeout: 60000 });

    mkdirSync(artifacts, { recursive: true });
    await page.screenshot({ path: path.join(artifacts, "prediction-band.png"), fullPage: true });
    assert.deepEqual(pageErrors, []);
  });
});
