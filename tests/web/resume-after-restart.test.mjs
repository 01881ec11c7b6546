// Browser test that nothing queued is lost: a fine job queued from the page on Redis survives a
// restart of the server. The page confirms (no worker yet, so the job waits on the stream), the
// server stops and starts again on the same port under the same replica name, the page reconnects
// by itself, opens the case again and resumes the job; a worker then runs it and the page shows
// it done. A real redis-server on a free port; skipped without it (failed under CI=true).
// Environment as harness.mjs says.
import { test } from "node:test";
import assert from "node:assert/strict";
import { spawn, spawnSync } from "node:child_process";
import { mkdirSync, mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { artifacts, cli, dataDir, startServer, waitForPage, withBrowser } from "./harness.mjs";

const haveRedis = spawnSync("sh", ["-c", "command -v redis-server"]).status === 0;
if (!haveRedis && process.env.CI === "true") throw new Error("redis-server is not on PATH (CI=true: scripts/setup-deps.sh installs it)");

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function startRedis(dir) {
  for (let attempt = 0; attempt < 5; ++attempt) {
    const port = 20000 + Math.floor(Math.random() * 30000);
    const redis = spawn("redis-server", ["--port", String(port), "--bind", "127.0.0.1", "--save", "", "--appendonly", "no",
      "--dir", dir], { stdio: "ignore" });
    for (let i = 0; i < 50; ++i) {
      if (spawnSync("redis-cli", ["-p", String(port), "ping"]).stdout?.toString().includes("PONG")) return { redis, port };
      if (redis.exitCode !== null) break;
      await sleep(100);
    }
    redis.kill("SIGKILL");
  }
  throw new Error("redis-server did not start");
}

function startWorker(url) {
  const worker = spawn(cli, ["worker", "--redis", url, "--data", dataDir, "--name", "page-resume-w1"], { stdio: ["ignore", "pipe", "inherit"] });
  const ready = new Promise((resolve, reject) => {
    let out = "";
    worker.stdout.on("data", (d) => { out += d; if (out.includes("worker ready")) resolve(); });
    worker.on("exit", (code) => reject(new Error(`orthosim worker exited with ${code}`)));
  });
  return { worker, ready };
}

const stopped = (child) => new Promise((resolve) => (child.exitCode !== null ? resolve(child.exitCode) : child.on("exit", resolve)));

test("a fine job queued from the page survives a server restart and is shown done", { timeout: 300000, skip: !haveRedis && "redis-server is not installed" }, async () => {
  const dir = mkdtempSync(path.join(tmpdir(), "orthosim-redis-"));
  const { redis, port: redisPort } = await startRedis(dir);
  const url = `redis://127.0.0.1:${redisPort}`;
  const args = ["--redis", url, "--replica", `page-${process.pid}`];
  const children = [redis];
  try {
    const first = startServer(dataDir, args);
    children.push(first.server);
    const port = await first.port;
    await withBrowser(async (page) => {
      const pageErrors = [];
      page.on("pageerror", (e) => pageErrors.push(e.message));
      const received = [];
      page.on("websocket", (ws) => ws.on("framereceived", (f) => {
        if (typeof f.payload === "string") received.push(JSON.parse(f.payload));
      }));
      await page.goto(`http://127.0.0.1:${port}/`);
      await waitForPage(page, () => document.querySelector("#case-select").options.length >= 1);
      await page.selectOption("#case-select", "phantom-0");
      await page.click("#open-case");
      await waitForPage(page, () => /Solved in/.test(document.querySelector("#preview-figures").textContent), null, { timeout: 120000 });
      await page.click("#confirm");
      await waitForPage(page, () => /queued/.test(document.querySelector("#job-status").textContent), null, { timeout: 30000 });
      const queued = received.find((m) => m.type === "job_queued");
      assert.ok(queued, "the job was queued");

      // The server stops (its job stays on Redis) and starts again on the same port.
      first.server.kill("SIGTERM");
      assert.equal(await stopped(first.server), 0, "a clean stop");
      await waitForPage(page, () => /disconnected/.test(document.querySelector("#connection").textContent), null, { timeout: 10000 });
      const second = startServer(dataDir, args, port);
      children.push(second.server);
      assert.equal(await second.port, port);

      // The page reconnects, opens the case again and resumes the job, which is still queued.
      await waitForPage(page, () => /resumed/.test(document.querySelector("#job-status").textContent), null, { timeout: 60000 });
      const resumed = received.find((m) => m.type === "resumed");
      assert.deepEqual(resumed.jobs.map((j) => j.job), [queued.job], JSON.stringify(resumed));
      assert.equal(resumed.jobs[0].state, "queued");

      // A worker comes: the job runs and the page shows it done.
      const { worker, ready } = startWorker(url);
      children.push(worker);
      await ready;
      await waitForPage(page, () => /done in/.test(document.querySelector("#job-status").textContent), null, { timeout: 180000 });
      const done = received.find((m) => m.type === "job_done");
      assert.equal(done.job, queued.job);
      assert.ok(done.figures.converged);
      mkdirSync(artifacts, { recursive: true });
      await page.screenshot({ path: path.join(artifacts, "resume-after-restart.png"), fullPage: true });
      assert.deepEqual(pageErrors, []);
    });
  } finally {
    for (const c of children.reverse()) c.kill("SIGKILL");
    rmSync(dir, { recursive: true, force: true });
  }
});
