// Browser end-to-end test of the Swarf web build.
//
// Serves target/web/ (built by `cargo xtask web`) on 127.0.0.1, opens it in headless Chromium
// (WebGL2 through SwiftShader; headless Chromium has no WebGPU canvas, so the app falls back to
// WebGL) and drives the page through `window.swarf`. Run with `node --test tests/e2e/`, or all
// tests with `cargo xtask test`.
//
// Environment: SWARF_WEB_DIR (default <repo>/target/web), SWARF_CHROMIUM (default
// /usr/bin/chromium).

import { after, before, test } from "node:test";
import assert from "node:assert/strict";
import { createServer } from "node:http";
import { mkdtemp, mkdir, readFile, rm, stat, writeFile } from "node:fs/promises";
import { existsSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { fileURLToPath } from "node:url";

import { chromium } from "playwright-core";
import { PNG } from "pngjs";

const HERE = path.dirname(fileURLToPath(import.meta.url));
const REPO = path.resolve(HERE, "..", "..");
const SITE = path.resolve(process.env.SWARF_WEB_DIR ?? path.join(REPO, "target", "web"));
const CHROMIUM = process.env.SWARF_CHROMIUM ?? "/usr/bin/chromium";
const ARTIFACTS = path.join(HERE, "artifacts");

const READY_TIMEOUT_MS = 120_000;
const TEST_TIMEOUT_MS = 180_000;

const CHROMIUM_ARGS = [
  "--headless",
  "--no-sandbox",
  "--disable-gpu",
  "--disable-quic",
  "--no-first-run",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
  "--enable-unsafe-swiftshader",
];

const MIME = {
  ".html": "text/html; charset=utf-8",
  ".js": "text/javascript; charset=utf-8",
  ".mjs": "text/javascript; charset=utf-8",
  ".css": "text/css; charset=utf-8",
  ".wasm": "application/wasm",
  ".png": "image/png",
  ".svg": "image/svg+xml",
  ".json": "application/json",
  ".ico": "image/x-icon",
};

let server;
let baseUrl;
let context;
let page;
let userDataDir;
let exampleMotions = 0;

/** Everything the page logged, in order, for failure messages. */
const consoleLog = [];
/** Console errors and uncaught page errors: the page must produce none. */
const pageErrors = [];

function logTail(lines = 60) {
  if (consoleLog.length === 0) {
    return "(the page logged nothing)";
  }
  const tail = consoleLog.slice(-lines);
  const skipped = consoleLog.length - tail.length;
  return (skipped > 0 ? `(… ${skipped} earlier lines)\n` : "") + tail.join("\n");
}

function withLog(message) {
  return `${message}\n--- browser console ---\n${logTail()}\n--- end of console ---`;
}

/** A static file server for SITE; 404 for anything outside it. */
function startServer() {
  const root = SITE + path.sep;
  const httpServer = createServer(async (request, response) => {
    try {
      const url = new URL(request.url ?? "/", "http://localhost");
      let file = path.normalize(path.join(SITE, decodeURIComponent(url.pathname)));
      if (!(file + path.sep).startsWith(root) && file !== SITE) {
        throw new Error("outside the site");
      }
      if ((await stat(file)).isDirectory()) {
        file = path.join(file, "index.html");
      }
      const body = await readFile(file);
      response.writeHead(200, {
        "Content-Type": MIME[path.extname(file).toLowerCase()] ?? "application/octet-stream",
        "Cache-Control": "no-store",
      });
      response.end(request.method === "HEAD" ? undefined : body);
    } catch {
      response.writeHead(404, { "Content-Type": "text/plain" });
      response.end("not found");
    }
  });
  return new Promise((resolve, reject) => {
    httpServer.once("error", reject);
    httpServer.listen(0, "127.0.0.1", () => resolve(httpServer));
  });
}

function withTimeout(promise, ms, what) {
  let timer;
  const timeout = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`${what}: timed out after ${ms / 1000} s`)), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

/** Polls `fn` in the page until `check(value)` holds; returns the value. */
async function eventually(fn, arg, check, what, timeoutMs = 30_000) {
  const deadline = Date.now() + timeoutMs;
  let value;
  for (;;) {
    value = await page.evaluate(fn, arg);
    if (check(value)) {
      return value;
    }
    if (Date.now() > deadline) {
      assert.fail(
        withLog(`${what} (waited ${timeoutMs / 1000} s); last value: ${JSON.stringify(value)}`),
      );
    }
    await new Promise((resolve) => setTimeout(resolve, 100));
  }
}

async function saveFailureScreenshot(name) {
  try {
    await mkdir(ARTIFACTS, { recursive: true });
    await page.screenshot({ path: path.join(ARTIFACTS, name) });
  } catch {
    // Best effort only.
  }
}

before(async () => {
  for (const file of ["index.html", "swarf.js", "swarf_app.js", "swarf_app_bg.wasm"]) {
    if (!existsSync(path.join(SITE, file))) {
      throw new Error(
        `${path.join(SITE, file)} is missing: build the web page first with \`cargo xtask web\``,
      );
    }
  }
  if (!existsSync(CHROMIUM)) {
    throw new Error(
      `${CHROMIUM} not found: install Debian's chromium (cargo xtask test does) or set SWARF_CHROMIUM`,
    );
  }
  server = await startServer();
  baseUrl = `http://127.0.0.1:${server.address().port}/`;

  userDataDir = await mkdtemp(path.join(tmpdir(), "swarf-e2e-chromium-"));
  context = await chromium.launchPersistentContext(userDataDir, {
    executablePath: CHROMIUM,
    headless: true,
    args: CHROMIUM_ARGS,
    viewport: { width: 1280, height: 800 },
    deviceScaleFactor: 1,
    timeout: 60_000,
  });
  page = context.pages()[0] ?? (await context.newPage());
  page.on("console", (message) => {
    const location = message.location();
    const where = location?.url ? ` (${location.url}:${location.lineNumber})` : "";
    const line = `[${message.type()}] ${message.text()}${where}`;
    consoleLog.push(line);
    if (message.type() === "error") {
      pageErrors.push(line);
    }
  });
  page.on("pageerror", (error) => {
    const line = `[pageerror] ${error.stack ?? error.message ?? String(error)}`;
    consoleLog.push(line);
    pageErrors.push(line);
  });
  page.on("requestfailed", (request) => {
    consoleLog.push(
      `[requestfailed] ${request.url()}: ${request.failure()?.errorText ?? "unknown error"}`,
    );
  });
  page.on("crash", () => {
    consoleLog.push("[crash] the page crashed");
    pageErrors.push("[crash] the page crashed");
  });
});

after(async () => {
  await context?.close().catch(() => {});
  await new Promise((resolve) => (server ? server.close(resolve) : resolve()));
  if (userDataDir) {
    await rm(userDataDir, { recursive: true, force: true }).catch(() => {});
  }
});

test("the page loads, becomes ready and shows the example program", { timeout: TEST_TIMEOUT_MS }, async () => {
  const response = await page.goto(baseUrl, { waitUntil: "load", timeout: 60_000 });
  assert.equal(response?.status(), 200, `GET ${baseUrl} answered ${response?.status()}`);

  await page
    .waitForFunction(() => typeof window.swarf === "object" && window.swarf !== null, null, {
      timeout: 30_000,
    })
    .catch(() => assert.fail(withLog("window.swarf was never defined: web/swarf.js did not run")));

  const outcome = await withTimeout(
    page.evaluate(async () => {
      try {
        await window.swarf.ready;
        return { ok: true };
      } catch (error) {
        return { ok: false, error: String(error?.stack ?? error) };
      }
    }),
    READY_TIMEOUT_MS,
    "waiting for window.swarf.ready",
  ).catch(async (error) => {
    await saveFailureScreenshot("not-ready.png");
    assert.fail(withLog(error.message));
  });
  if (!outcome.ok) {
    await saveFailureScreenshot("not-ready.png");
    const shown = await page.locator("#swarf-status").innerText().catch(() => "");
    assert.fail(
      withLog(`window.swarf.ready rejected: ${outcome.error}\npage shows: ${shown.trim()}`),
    );
  }

  assert.equal(
    await page.locator("#swarf-status").isVisible(),
    false,
    "the loading message is still visible after ready",
  );

  const text = await page.evaluate(() => window.swarf.getText());
  assert.equal(typeof text, "string", "getText() must return a string");
  assert.ok(text.trim().length > 0, "the editor is empty: the example program was not loaded");

  const stats = await eventually(
    () => window.swarf.stats(),
    null,
    (s) => s && s.motions > 0 && s.bounds !== null,
    "stats() of the example program should report motions > 0 and bounds",
  );
  assert.ok(Number.isInteger(stats.blocks) && stats.blocks > 0, `stats().blocks: ${stats.blocks}`);
  for (const corner of ["min", "max"]) {
    const point = stats.bounds[corner];
    assert.ok(
      Array.isArray(point) && point.length === 3 && point.every(Number.isFinite),
      `stats().bounds.${corner} should be [x, y, z], got ${JSON.stringify(point)}`,
    );
  }
  exampleMotions = stats.motions;
});

test("the backplot canvas is not blank", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");
  const canvas = page.locator("#swarf-canvas");
  const box = await canvas.boundingBox();
  assert.ok(
    box && box.width >= 1200 && box.height >= 700,
    `the canvas should fill the 1280x800 window, its box is ${JSON.stringify(box)}`,
  );

  // Give egui a few frames to lay out and the backplot to draw, then retry for a while.
  const deadline = Date.now() + 30_000;
  let result;
  let png;
  for (;;) {
    await page.waitForTimeout(500);
    png = await canvas.screenshot({ timeout: 30_000 });
    result = analyse(PNG.sync.read(png));
    if (result.differing >= 500 && result.distinct > 16) {
      break;
    }
    if (Date.now() > deadline) {
      break;
    }
  }
  await mkdir(ARTIFACTS, { recursive: true });
  await writeFile(path.join(ARTIFACTS, "screenshot.png"), png);
  assert.ok(
    result.differing >= 500 && result.distinct > 16,
    withLog(
      `the canvas looks blank: ${result.differing} of ${result.total} pixels differ from the ` +
        `dominant colour rgba(${result.dominant}), ${result.distinct} distinct colours ` +
        `(expected >= 500 and > 16); see ${path.join(ARTIFACTS, "screenshot.png")}`,
    ),
  );
});

/** Counts distinct colours and pixels that differ from the most common colour. */
function analyse(image) {
  const counts = new Map();
  const { data } = image;
  for (let i = 0; i < data.length; i += 4) {
    const key = ((data[i] << 24) | (data[i + 1] << 16) | (data[i + 2] << 8) | data[i + 3]) >>> 0;
    counts.set(key, (counts.get(key) ?? 0) + 1);
  }
  let dominantKey = 0;
  let dominantCount = 0;
  for (const [key, count] of counts) {
    if (count > dominantCount) {
      dominantKey = key;
      dominantCount = count;
    }
  }
  const total = data.length / 4;
  const dominant = [24, 16, 8, 0].map((shift) => (dominantKey >>> shift) & 0xff).join(",");
  return { total, distinct: counts.size, differing: total - dominantCount, dominant };
}

test("diagnostics follow the edited text", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  const broken = "G90 G21\nG00 X0 Y0 Z5\nG01 X10 Y$ F100\n";
  await page.evaluate((text) => window.swarf.setText(text), broken);
  assert.equal(await page.evaluate(() => window.swarf.getText()), broken, "getText() after setText()");
  const isError = (d) => String(d.severity).toLowerCase() === "error";
  await eventually(
    () => window.swarf.diagnostics(),
    null,
    (list) => Array.isArray(list) && list.some((d) => d.line === 3 && isError(d)),
    "diagnostics() should report an error on line 3 for `Y$`",
  );

  // A square pocket outline: 2 feeds down/up and the 4 sides, all in mm.
  const square =
    "G90 G21 G17\nG00 X0 Y0 Z5\nG01 Z-1 F100\nG01 X30\nG01 Y20\nG01 X0\nG01 Y0\nG00 Z5\nM30\n";
  await page.evaluate((text) => window.swarf.setText(text), square);
  await eventually(
    () => window.swarf.diagnostics(),
    null,
    (list) => Array.isArray(list) && !list.some(isError),
    "diagnostics() should have no errors for a valid program",
  );
  const stats = await eventually(
    () => window.swarf.stats(),
    null,
    (s) => s && s.motions >= 5 && s.bounds !== null && Math.abs(s.bounds.max[0] - 30) < 1e-6,
    "stats() should report the square's motions and bounds (max X = 30)",
  );
  const near = (a, b) => Math.abs(a - b) < 1e-6;
  assert.ok(near(stats.bounds.max[1], 20), `bounds.max Y should be 20: ${JSON.stringify(stats)}`);
  assert.ok(near(stats.bounds.min[2], -1), `bounds.min Z should be -1: ${JSON.stringify(stats)}`);

  // A longer program must give more motions: stats follow every edit.
  const twice = square.replace("M30\n", "G01 Z-2\nG01 X30\nG01 Y20\nG00 Z5\nM30\n");
  await page.evaluate((text) => window.swarf.setText(text), twice);
  await eventually(
    () => window.swarf.stats(),
    null,
    (s) => s && s.motions > stats.motions,
    `stats().motions should grow past ${stats.motions} after adding moves`,
  );
});

test("no console errors or page errors", () => {
  assert.deepEqual(
    pageErrors,
    [],
    withLog(`the page reported ${pageErrors.length} error(s):\n${pageErrors.join("\n")}`),
  );
});
