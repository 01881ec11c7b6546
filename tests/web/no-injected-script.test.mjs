// Browser test: text a user supplied never runs as script on the planning page. A patient uploaded
// with markup as its name (`<img src=x onerror=...>`) and a surgeon's name made of markup are shown
// literally wherever the page shows them (case list, import status, messages, saved plans) and
// nothing they carry runs; every reply carries the Content-Security-Policy, under which an inline
// script and an event-handler attribute put into the page are blocked (securitypolicyviolation).
// Also the plan flow: the surgeon's name is kept in localStorage and sent with save_plan; saving
// over a saved name asks first, naming who saved it and when, and replaces only when confirmed.
// Environment as harness.mjs says.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { cli, waitForPage, withPage } from "./harness.mjs";

const PATIENT = "<img src=x onerror=window.__pwned=1>";
const SURGEON = "<img src=x onerror=window.__pwned=2> Dr. O'Brien";

// The policy must forbid inline script; these are the parts the page relies on.
function checkPolicy(csp, where) {
  assert.ok(csp, `${where}: a Content-Security-Policy header`);
  for (const part of ["default-src 'self'", "script-src 'self'", "object-src 'none'", "base-uri 'none'",
    "frame-ancestors 'none'"])
    assert.ok(csp.split(";").map((d) => d.trim()).includes(part), `${where}: ${part} in ${csp}`);
  assert.doesNotMatch(csp, /unsafe-inline|unsafe-eval/, `${where}: ${csp}`);
}

// The texts a selector's elements show, and the number of <img> elements inside them.
async function shown(page, selector) {
  return page.evaluate((s) => [...document.querySelectorAll(s)].map((e) => ({
    text: e.textContent, images: e.querySelectorAll("img").length })), selector);
}

test("no injected script runs: user texts shown literally, CSP blocks inline script", { timeout: 560000 }, async () => {
  const work = mkdtempSync(path.join(tmpdir(), "orthosim-no-script-"));
  try {
    const exported = path.join(work, "export");
    execFileSync(cli, ["phantom", "--out", exported, "--variant", "0"], { stdio: "ignore" });
    const file = (name) => path.join(exported, name);
    await withPage(async (page, url) => {
      const pageErrors = [];
      page.on("pageerror", (e) => pageErrors.push(e.message));
      // Every policy violation from the first script on, and what went over the WebSocket.
      await page.addInitScript(() => {
        window.__violations = [];
        document.addEventListener("securitypolicyviolation",
          (e) => window.__violations.push({ directive: e.violatedDirective, sample: e.sample }));
      });
      const sent = [], received = [];
      page.on("websocket", (ws) => {
        ws.on("framesent", (f) => { if (typeof f.payload === "string") sent.push(JSON.parse(f.payload)); });
        ws.on("framereceived", (f) => { if (typeof f.payload === "string") received.push(JSON.parse(f.payload)); });
      });

      // The policy on the page, an API reply and an error.
      const response = await page.goto(url);
      checkPolicy(response.headers()["content-security-policy"], "/");
      for (const target of ["api/health", "no-such-file"])
        checkPolicy((await fetch(url + target)).headers.get("content-security-policy"), target);

      // The surgeon's name is asked once: kept in localStorage across a reload.
      await page.fill("#user-name", SURGEON);
      await page.reload();
      assert.equal(await page.inputValue("#user-name"), SURGEON, "the name is kept");

      // A patient whose name is markup.
      await waitForPage(page, () => document.querySelector("#case-select").options.length >= 1);
      await page.click("#new-patient summary");
      await page.fill('input[aria-label="case id"]', "markup-name");
      await page.fill('input[aria-label="patient name"]', PATIENT);
      await page.setInputFiles('input[aria-label="skin file"]', file("skin.obj"));
      await page.setInputFiles('input[aria-label="skull file"]', file("skull.stl"));
      await page.setInputFiles('input[aria-label="mandible file"]', file("mandible.stl"));
      await page.setInputFiles('input[aria-label="cavity files"]', file("oral_cavity.stl"));
      await page.setInputFiles('input[aria-label="landmarks file"]', file("landmarks.json"));
      await page.click("#import-patient");
      await waitForPage(page, () => /imported/.test(document.querySelector("#import-status").textContent), null, { timeout: 180000 })
        .catch(async (e) => { console.log("import-status:", await page.locator("#import-status").textContent()); throw e; });
      const slider = page.locator('input[aria-label="maxilla anterior_mm"]');
      await slider.waitFor({ timeout: 240000 });
      assert.equal(await page.locator("#case-select").inputValue(), "markup-name");

      // Saved, then saved again under the same name: refused, asked, kept when dismissed, replaced
      // when confirmed.
      const dialogs = [];
      const answer = (accept) => page.once("dialog", async (d) => { dialogs.push(d.message()); await (accept ? d.accept() : d.dismiss()); });
      const savedCount = () => received.filter((m) => m.type === "saved").length;
      await page.fill("#plan-name", "plan-a");
      await page.click("#save-plan");
      await waitForPage(page, () => document.querySelector("#plan-list").options.length === 1, null, { timeout: 30000 });
      assert.equal(savedCount(), 1);
      const firstSave = sent.find((m) => m.type === "save_plan");
      assert.equal(firstSave.saved_by, SURGEON, "the name goes with save_plan");
      assert.equal(firstSave.replace, undefined, "a first save asks for no replace");
      const savedAt = received.find((m) => m.type === "saved").saved_at;
      assert.match(savedAt, /^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ$/);

      answer(false);
      await page.click("#save-plan");
      await waitForPage(page, () => /not saved: the saved one is kept/.test(document.querySelector("#messages").textContent), null, { timeout: 30000 });
      assert.equal(dialogs.length, 1, "the surgeon was asked");
      assert.ok(dialogs[0].includes(SURGEON) && dialogs[0].includes(savedAt), `the question names who and when: ${dialogs[0]}`);
      assert.ok(received.some((m) => m.type === "error" && m.error === "plan_exists"));
      assert.equal(savedCount(), 1, "dismissed: not saved");

      answer(true);
      await page.click("#save-plan");
      const by = Date.now() + 30000;
      while (savedCount() < 2 && Date.now() < by) await page.waitForTimeout(100);
      assert.equal(savedCount(), 2, "confirmed: replaced");
      assert.equal(dialogs.length, 2);
      assert.equal(sent.filter((m) => m.type === "save_plan").at(-1).replace, true);

      // Every place the page shows those texts shows them as text.
      await waitForPage(page, () => document.querySelector("#plan-list").options.length === 1);
      const places = {
        "#case-select option": PATIENT, "#import-status": PATIENT, "#messages": PATIENT,
        "#plan-list option": SURGEON,
      };
      for (const [selector, text] of Object.entries(places)) {
        const found = await shown(page, selector);
        assert.ok(found.some((e) => e.text.includes(text)), `${selector} shows ${text} literally: ${JSON.stringify(found)}`);
        assert.ok(found.every((e) => e.images === 0), `${selector} holds no element made of it`);
      }
      assert.equal(await page.evaluate(() => document.querySelectorAll("img:not(#frame):not(#report-plot)").length), 0,
        "no image element was made of a text");
      assert.equal(await page.evaluate(() => window.__pwned), undefined, "nothing the texts carry ran");
      assert.deepEqual(await page.evaluate(() => window.__violations), [], "the page itself needs nothing the policy forbids");

      // Script put into the page is blocked: an inline <script> and an event-handler attribute.
      await page.evaluate(() => {
        const script = document.createElement("script");
        script.textContent = "window.__inline = 1;";
        document.body.append(script);
        const box = document.createElement("div");
        box.innerHTML = '<img src="data:," onerror="window.__attribute = 1">';  // the test's own injection
        document.body.append(box);
      });
      await waitForPage(page, () => window.__violations.length >= 2, null, { timeout: 10000 })
        .catch(() => {});
      const violations = await page.evaluate(() => window.__violations);
      assert.equal(await page.evaluate(() => window.__inline), undefined, "the inline script did not run");
      assert.equal(await page.evaluate(() => window.__attribute), undefined, "the onerror attribute did not run");
      const directives = violations.map((v) => v.directive);
      assert.ok(directives.includes("script-src-elem"), JSON.stringify(violations));
      assert.ok(directives.includes("script-src-attr"), JSON.stringify(violations));
      assert.deepEqual(pageErrors, [], "no script errors on the page");
    }, { dataDir: path.join(work, "data") });
  } finally {
    rmSync(work, { recursive: true, force: true });
  }
});
