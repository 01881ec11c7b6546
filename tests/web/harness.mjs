// What the browser tests share: a real `orthosim serve` on a free port and Debian's Chromium in a
// fresh profile, headless with the flags the machine needs (../shared/notes/debian-recipes.md).
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { chromium } from "playwright-core";

export const cli = process.env.ORTHOSIM_CLI;
export const dataDir = process.env.ORTHOSIM_TEST_DATA;
export const artifacts = process.env.ARTIFACT_DIR || ".";

// `orthosim serve` on `port` (0: a free one) with `extraArgs`; { server, port: Promise }.
export function startServer(data = dataDir, extraArgs = [], port0 = 0) {
  const server = spawn(cli, ["serve", "--port", String(port0), "--data", data, "--no-warm-up", ...extraArgs],
    { stdio: ["ignore", "pipe", "inherit"] });
  const port = new Promise((resolve, reject) => {
    let out = "";
    server.stdout.on("data", (d) => {
      out += d;
      const m = out.match(/listening on http:\/\/127\.0\.0\.1:(\d+)/);
      if (m) resolve(Number(m[1]));
    });
    server.on("exit", (code) => reject(new Error(`orthosim serve exited with ${code}`)));
    // unref: a pending timer would keep node (and the test) alive for its 30 s after the test.
    setTimeout(() => reject(new Error("orthosim serve did not start in 30 s")), 30000).unref();
  });
  return { server, port };
}

// Runs body(page, url) against a fresh server (on `options.dataDir`, default the shared test data
// folder) and browser; both are closed whatever happens.
export async function withPage(body, options = {}) {
  if (!cli) throw new Error("ORTHOSIM_CLI must name the orthosim executable");
  const { server, port } = startServer(options.dataDir || dataDir);
  try {
    const url = `http://127.0.0.1:${await port}/`;
    await withBrowser((page) => body(page, url));
  } finally {
    server.kill("SIGTERM");
  }
}

// Runs body(page) in a fresh headless Chromium profile, closed whatever happens.
export async function withBrowser(body) {
  const userData = mkdtempSync(path.join(tmpdir(), "orthosim-chromium-"));
  let context;
  try {
    context = await chromium.launchPersistentContext(userData, {
      executablePath: "/usr/bin/chromium",
      headless: true,
      viewport: { width: 1280, height: 900 },
      args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
        "--disable-background-networking", "--disable-component-update", "--disable-sync"],
    });
    const page = context.pages()[0] || (await context.newPage());
    await body(page);
  } finally {
    if (context) await context.close();
    rmSync(userData, { recursive: true, force: true });
  }
}

// Waits until `predicate(arg)`, run in the page, is truthy, and returns its value; as
// page.waitForFunction, which cannot serve here: it evaluates the predicate with eval() inside the
// page, and the page's Content-Security-Policy forbids eval. page.evaluate runs through the DevTools
// protocol, which the policy does not govern, so the page is tested under its real policy.
export async function waitForPage(page, predicate, arg, options = {}) {
  const timeout = options.timeout ?? 30000;
  const deadline = Date.now() + timeout;
  for (;;) {
    try {
      const value = await page.evaluate(predicate, arg);
      if (value) return value;
    } catch (e) {
      if (!/Execution context was destroyed|navigat/i.test(e.message)) throw e;  // a reload: try again
    }
    if (Date.now() > deadline)
      throw new Error(`waitForPage: ${timeout} ms passed waiting for ${String(predicate).slice(0, 300)}`);
    await new Promise((resolve) => setTimeout(resolve, 50));
  }
}
