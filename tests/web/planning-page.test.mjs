// Browser test of the planning page (issue 6): Debian's Chromium, headless, driven by
// playwright-core, against a real `orthosim serve` started here. Opens the phantom, moves the
// maxilla advancement slider, sees a new frame and a solve time, confirms on the fine model to
// 100 %, and saves a screenshot as a test artefact.
// Environment: ORTHOSIM_CLI (the executable), ORTHOSIM_TEST_DATA (server data folder),
// ARTIFACT_DIR (where the screenshot goes).
import { test } from "node:test";
import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync, mkdirSync, statSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { chromium } from "playwright-core";

const cli = process.env.ORTHOSIM_CLI;
const dataDir = process.env.ORTHOSIM_TEST_DATA;
const artifacts = process.env.ARTIFACT_DIR || ".";

function startServer() {
  const server = spawn(cli, ["serve", "--port", "0", "--data", dataDir, "--no-warm-up"], { stdio: ["ignore", "pipe", "inherit"] });
  const port = new Promise((resolve, reject) => {
    let out = "";
    server.stdout.on("data", (d) => {
      out += d;
      const m = out.match(/listening on http:\/\/127\.0\.0\.1:(\d+)/);
      if (m) resolve(Number(m[1]));
    });
    server.on("exit", (code) => reject(new Error(`orthosim serve exited with ${code}`)));
    setTimeout(() => reject(new Error("orthosim serve did not start in 30 s")), 30000);
  });
  return { server, port };
}

test("planning page: slider preview, fine confirm, screenshot", { timeout: 300000 }, async () => {
  assert.ok(cli, "ORTHOSIM_CLI must name the orthosim executable");
  const { server, port } = startServer();
  const userData = mkdtempSync(path.join(tmpdir(), "orthosim-chromium-"));
  let context;
  try {
    const url = `http://127.0.0.1:${await port}/`;
    context = await chromium.launchPersistentContext(userData, {
      executablePath: "/usr/bin/chromium",
      headless: true,
      viewport: { width: 1280, height: 900 },
      args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"],
    });
    const page = context.pages()[0] || (await context.newPage());
    const pageErrors = [];
    page.on("pageerror", (e) => pageErrors.push(e.message));
    await page.goto(url);
    await page.waitForFunction(() => document.querySelector("#case-select").options.length >= 5);
    await page.selectOption("#case-select", "phantom-0");
    await page.click("#open-case");

    // The face arrives as a streamed frame, then the preview of the rest pose.
    const slider = page.locator('input[aria-label="maxilla anterior_mm"]');
    await slider.waitFor({ timeout: 120000 });
    await page.waitForFunction(() => document.querySelector("#frame").src.startsWith("blob:"), null, { timeout: 60000 });
    await page.waitForFunction(() => /Solved in/.test(document.querySelector("#preview-figures").textContent), null, { timeout: 60000 });
    const before = await page.locator("#frame").getAttribute("src");

    // Drag-like input: 40 key presses of 0.1 mm move the maxilla 4 mm forward.
    await slider.focus();
    for (let i = 0; i < 40; i++) await page.keyboard.press("ArrowRight");
    assert.equal(Number(await slider.inputValue()), 4);
    await page.waitForFunction(
      (old) => document.querySelector("#frame").src !== old &&
        /upper lip/.test(document.querySelector("#preview-figures").textContent), before, { timeout: 60000 });
    // The newest pose is the one shown once the previews catch up.
    await page.waitForFunction(() => {
      const rows = [...document.querySelectorAll("#preview-figures tr")];
      const lip = rows.find((r) => /upper lip/.test(r.textContent));
      return lip && Number(lip.children[1].textContent) > 2.0;
    }, null, { timeout: 60000 });
    const solve = await page.locator("#solve-time").textContent();
    assert.match(solve, /Solved in \d+\.\d+ s/);

    // View buttons and mouse orbit redraw the face.
    await page.click('#views button[data-view="profile"]');
    await page.waitForFunction(() => /profile view/.test(document.querySelector("#frame-info").textContent), null, { timeout: 30000 });
    const profile = await page.locator("#frame").getAttribute("src");
    const box = await page.locator("#frame-box").boundingBox();
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.mouse.down();
    await page.mouse.move(box.x + box.width / 2 + 120, box.y + box.height / 2, { steps: 6 });
    await page.mouse.up();
    await page.waitForFunction((old) => document.querySelector("#frame").src !== old, profile, { timeout: 30000 });

    // Fine confirm to 100 %.
    await page.click("#confirm");
    await page.waitForFunction(() => /done/.test(document.querySelector("#job-status").textContent), null, { timeout: 240000 });
    assert.equal(Number(await page.locator("#job-progress").evaluate((p) => p.value)), 1);
    assert.match(await page.locator("#job-status").textContent(), /Coarse vs fine on the skin/);
    await page.waitForFunction(() => /difference/.test(document.querySelector("#frame-info").textContent), null, { timeout: 30000 })
      .catch(async (e) => { console.log("frame-info:", await page.locator("#frame-info").textContent(), await page.locator("#messages").textContent()); throw e; });

    mkdirSync(artifacts, { recursive: true });
    const shot = path.join(artifacts, "planning-page.png");
    await page.screenshot({ path: shot, fullPage: true });
    assert.ok(statSync(shot).size > 20000, "the screenshot shows the page");
    assert.deepEqual(pageErrors, [], "no script errors on the page");
  } finally {
    if (context) await context.close();
    server.kill("SIGTERM");
    rmSync(userData, { recursive: true, force: true });
  }
});
