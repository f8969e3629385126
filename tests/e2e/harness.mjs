// Shared helpers of the browser end-to-end tests (`*.test.mjs` in this folder): the web build
// served by `cargo xtask serve`, a Chromium session that records the page's console, and the checks that
// every variant makes. Not a test file itself (`node --test` only runs `*.test.mjs` here).
//
// Environment: SWARF_WEB_DIR (default <repo>/target/web), SWARF_CHROMIUM (default
// /usr/bin/chromium), SWARF_XTASK (the xtask program to serve the page with; default
// `cargo run --package xtask`).

import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { mkdtemp, mkdir, rm, writeFile } from "node:fs/promises";
import { existsSync } from "node:fs";
import { tmpdir } from "node:os";
import path from "node:path";
import { after, before } from "node:test";
import { fileURLToPath } from "node:url";

import { chromium } from "playwright-core";
import { PNG } from "pngjs";

const HERE = path.dirname(fileURLToPath(import.meta.url));
const REPO = path.resolve(HERE, "..", "..");
export const SITE = path.resolve(process.env.SWARF_WEB_DIR ?? path.join(REPO, "target", "web"));
export const CHROMIUM = process.env.SWARF_CHROMIUM ?? "/usr/bin/chromium";
const XTASK = process.env.SWARF_XTASK;
export const ARTIFACTS = path.join(HERE, "artifacts");

export const READY_TIMEOUT_MS = 120_000;
export const TEST_TIMEOUT_MS = 180_000;

/** Chromium flags of every variant: no sandbox (root in CI), nothing that phones home. */
export const COMMON_CHROMIUM_ARGS = [
  "--no-sandbox",
  "--disable-quic",
  "--no-first-run",
  "--disable-background-networking",
  "--disable-component-update",
  "--disable-sync",
];

/** Flags of the headless variant: WebGL2 through SwiftShader. */
export const HEADLESS_ARGS = ["--headless", "--disable-gpu", "--enable-unsafe-swiftshader"];

/**
 * One headless session for the calling test file: started before its tests (after checking the
 * prerequisites) and closed after them; the returned function gives it.
 */
export function headlessSession() {
  let session;
  before(async () => {
    checkPrerequisites();
    session = await BrowserSession.start({ headless: true, args: HEADLESS_ARGS });
  });
  after(async () => {
    await session?.close();
  });
  return () => session;
}

/** Throws a readable error when the web build or Chromium is missing. */
export function checkPrerequisites() {
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
}

/**
 * Serves SITE through `cargo xtask serve --no-build` on a free port of 127.0.0.1, the server a
 * person runs (it sends the precompressed copies of the files); resolves to the child process
 * and the page's URL.
 */
function startServer() {
  const serve = ["serve", "--no-build", "--port", "0", "--dir", SITE];
  const [program, args] = XTASK
    ? [XTASK, serve]
    : ["cargo", ["run", "--quiet", "--package", "xtask", "--", ...serve]];
  const server = spawn(program, args, { cwd: REPO, stdio: ["ignore", "pipe", "pipe"] });
  const stopOnExit = () => server.kill();
  process.once("exit", stopOnExit);
  server.once("exit", () => process.off("exit", stopOnExit));
  let output = "";
  return new Promise((resolve, reject) => {
    const failed = (why) => reject(new Error(`cargo xtask serve ${why}:\n${output}`));
    server.stderr.on("data", (chunk) => (output += chunk));
    server.stdout.on("data", (chunk) => {
      output += chunk;
      const address = /running at (http:\/\/127\.0\.0\.1:\d+\/)/.exec(output);
      if (address) {
        resolve({ server, url: address[1] });
      }
    });
    server.once("error", (error) => failed(`did not start (${error.message})`));
    server.once("exit", (code, signal) => failed(`stopped (${signal ?? `exit code ${code}`})`));
  });
}

function withTimeout(promise, ms, what) {
  let timer;
  const timeout = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`${what}: timed out after ${ms / 1000} s`)), ms);
  });
  return Promise.race([promise, timeout]).finally(() => clearTimeout(timer));
}

/**
 * The web build served on 127.0.0.1 (a secure context, as WebGPU requires) and one Chromium
 * page, with everything the page logs.
 */
export class BrowserSession {
  /** Everything the page logged, in order, for failure messages. */
  consoleLog = [];
  /** Console errors and uncaught page errors: the page must produce none. */
  pageErrors = [];

  /**
   * Starts the server and Chromium (`headless`: the old headless mode via `--headless` in
   * `args`, or a headed window on $DISPLAY) with COMMON_CHROMIUM_ARGS plus `args`.
   */
  static async start({ headless, args }) {
    const session = new BrowserSession();
    try {
      await session.#start(headless, args);
    } catch (error) {
      await session.close();
      throw error;
    }
    return session;
  }

  async #start(headless, args) {
    const { server, url } = await startServer();
    this.server = server;
    this.baseUrl = url;

    this.userDataDir = await mkdtemp(path.join(tmpdir(), "swarf-e2e-chromium-"));
    this.context = await chromium.launchPersistentContext(this.userDataDir, {
      executablePath: CHROMIUM,
      headless,
      args: [...COMMON_CHROMIUM_ARGS, ...args],
      viewport: { width: 1280, height: 800 },
      deviceScaleFactor: 1,
      timeout: 60_000,
    });
    this.page = this.context.pages()[0] ?? (await this.context.newPage());
    const { consoleLog, pageErrors } = this;
    this.page.on("console", (message) => {
      const location = message.location();
      const where = location?.url ? ` (${location.url}:${location.lineNumber})` : "";
      const line = `[${message.type()}] ${message.text()}${where}`;
      consoleLog.push(line);
      if (message.type() === "error") {
        pageErrors.push(line);
      }
    });
    this.page.on("pageerror", (error) => {
      const line = `[pageerror] ${error.stack ?? error.message ?? String(error)}`;
      consoleLog.push(line);
      pageErrors.push(line);
    });
    this.page.on("requestfailed", (request) => {
      consoleLog.push(
        `[requestfailed] ${request.url()}: ${request.failure()?.errorText ?? "unknown error"}`,
      );
    });
    this.page.on("crash", () => {
      consoleLog.push("[crash] the page crashed");
      pageErrors.push("[crash] the page crashed");
    });
  }

  /**
   * Intercepts the page's file choosers from now on; `nextFileChooser()` hands them out.
   * Call it well before a chooser is due: Playwright turns interception on when a listener is
   * added, without waiting for Chromium, which may acknowledge it only a second or two later
   * on a busy page. A chooser opened in between is not intercepted and never reported.
   */
  interceptFileChoosers() {
    this.fileChoosers = [];
    this.fileChooserWaiters = [];
    this.page.on("filechooser", (chooser) => {
      const waiter = this.fileChooserWaiters.shift();
      if (waiter) {
        waiter(chooser);
      } else {
        this.fileChoosers.push(chooser);
      }
    });
  }

  /** The next file chooser the page opens (see `interceptFileChoosers`), within `timeoutMs`. */
  nextFileChooser(timeoutMs = 30_000) {
    assert.ok(this.fileChooserWaiters, "call interceptFileChoosers() first");
    const queued = this.fileChoosers.shift();
    if (queued) {
      return Promise.resolve(queued);
    }
    let waiter;
    const next = new Promise((resolve) => {
      waiter = resolve;
      this.fileChooserWaiters.push(resolve);
    });
    return withTimeout(next, timeoutMs, "waiting for a file chooser").catch((error) => {
      this.fileChooserWaiters = this.fileChooserWaiters.filter((w) => w !== waiter);
      throw error;
    });
  }

  /** Stops the server (the page's files are then only where the browser keeps them). */
  async stopServer() {
    const { server } = this;
    this.server = undefined;
    if (server && server.exitCode === null && server.signalCode === null) {
      const exited = new Promise((resolve) => server.once("exit", resolve));
      server.kill();
      await exited;
    }
  }

  async close() {
    await this.context?.close().catch(() => {});
    await this.stopServer();
    if (this.userDataDir) {
      await rm(this.userDataDir, { recursive: true, force: true }).catch(() => {});
    }
  }

  logTail(lines = 60) {
    if (this.consoleLog.length === 0) {
      return "(the page logged nothing)";
    }
    const tail = this.consoleLog.slice(-lines);
    const skipped = this.consoleLog.length - tail.length;
    return (skipped > 0 ? `(… ${skipped} earlier lines)\n` : "") + tail.join("\n");
  }

  withLog(message) {
    return `${message}\n--- browser console ---\n${this.logTail()}\n--- end of console ---`;
  }

  /** Polls `fn` in the page until `check(value)` holds; returns the value. */
  async eventually(fn, arg, check, what, timeoutMs = 30_000) {
    const deadline = Date.now() + timeoutMs;
    let value;
    for (;;) {
      value = await this.page.evaluate(fn, arg);
      if (check(value)) {
        return value;
      }
      if (Date.now() > deadline) {
        assert.fail(
          this.withLog(
            `${what} (waited ${timeoutMs / 1000} s); last value: ${JSON.stringify(value)}`,
          ),
        );
      }
      await new Promise((resolve) => setTimeout(resolve, 100));
    }
  }

  /**
   * Waits for `window.swarf.idle()`: the current text's analysis is finished and a frame
   * showing it was painted, so `diagnostics()` and `stats()` describe the current text.
   */
  async idle(timeoutMs = 60_000) {
    await withTimeout(
      this.page.evaluate(() => window.swarf.idle()),
      timeoutMs,
      "waiting for window.swarf.idle()",
    ).catch((error) => assert.fail(this.withLog(error.message)));
  }

  async saveFailureScreenshot(name) {
    try {
      await mkdir(ARTIFACTS, { recursive: true });
      await this.page.screenshot({ path: path.join(ARTIFACTS, name) });
    } catch {
      // Best effort only.
    }
  }

  /**
   * Loads the page and waits for `window.swarf.ready`; on failure saves `failureScreenshot`
   * under ARTIFACTS and fails with the page's message and console.
   */
  async loadUntilReady(failureScreenshot) {
    const { page, baseUrl } = this;
    const response = await page.goto(baseUrl, { waitUntil: "load", timeout: 60_000 });
    assert.equal(response?.status(), 200, `GET ${baseUrl} answered ${response?.status()}`);

    await page
      .waitForFunction(() => typeof window.swarf === "object" && window.swarf !== null, null, {
        timeout: 30_000,
      })
      .catch(() =>
        assert.fail(this.withLog("window.swarf was never defined: web/swarf.js did not run")),
      );

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
      await this.saveFailureScreenshot(failureScreenshot);
      assert.fail(this.withLog(error.message));
    });
    if (!outcome.ok) {
      await this.saveFailureScreenshot(failureScreenshot);
      const shown = await page.locator("#swarf-status").innerText().catch(() => "");
      assert.fail(
        this.withLog(`window.swarf.ready rejected: ${outcome.error}\npage shows: ${shown.trim()}`),
      );
    }

    assert.equal(
      await page.locator("#swarf-status").isVisible(),
      false,
      "the loading message is still visible after ready",
    );
  }

  /**
   * Checks that the canvas fills the window and, within 30 s, shows a drawing rather than one
   * flat colour; saves its screenshot as ARTIFACTS/`artifact`.
   */
  async assertCanvasNotBlank(artifact) {
    const canvas = this.page.locator("#swarf-canvas");
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
      await this.page.waitForTimeout(500);
      png = await canvas.screenshot({ timeout: 30_000 });
      result = analyse(PNG.sync.read(png));
      if (result.differing >= 500 && result.distinct > 16) {
        break;
      }
      if (Date.now() > deadline) {
        break;
      }
    }
    const file = path.join(ARTIFACTS, artifact);
    await mkdir(ARTIFACTS, { recursive: true });
    await writeFile(file, png);
    assert.ok(
      result.differing >= 500 && result.distinct > 16,
      this.withLog(
        `the canvas looks blank: ${result.differing} of ${result.total} pixels differ from the ` +
          `dominant colour rgba(${result.dominant}), ${result.distinct} distinct colours ` +
          `(expected >= 500 and > 16); see ${file}`,
      ),
    );
  }

  /** Fails with the page's errors, if it reported any. */
  assertNoPageErrors() {
    assert.deepEqual(
      this.pageErrors,
      [],
      this.withLog(
        `the page reported ${this.pageErrors.length} error(s):\n${this.pageErrors.join("\n")}`,
      ),
    );
  }
}

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

/**
 * A program of `moves` feeds in rows of `perRow`, 0.25 mm apart along X and rows 0.5 mm apart,
 * over a gentle wave in Z: far more moves than a fitted view can show apart.
 */
export function rasterProgram(moves, perRow) {
  const lines = ["G90 G21 G17", "G00 X0 Y0 Z5.", "G01 Z0. F1500."];
  for (let n = 0; n < moves; n++) {
    const x = (n % perRow) * 0.25;
    const y = Math.floor(n / perRow) * 0.5;
    lines.push(`G01 X${x.toFixed(2)} Y${y.toFixed(1)} Z${(-Math.abs(Math.sin(x * 0.07)) * 3).toFixed(3)}`);
  }
  lines.push("M30", "");
  return lines.join("\n");
}

/** Whether a `window.swarf.diagnostics()` entry is an error (the severity in any case). */
export function isError(diagnostic) {
  return String(diagnostic.severity).toLowerCase() === "error";
}

/**
 * What the page keeps for crash recovery in IndexedDB: `{ index, records }` — the index text
 * and every tab record's text by key — or `null` while nothing is stored.
 */
export function recoveryRecords(page) {
  return page.evaluate(async () => {
    const known = await indexedDB.databases();
    if (!known.some((d) => d.name === "swarf-recovery")) {
      return null;
    }
    const db = await new Promise((resolve, reject) => {
      const open = indexedDB.open("swarf-recovery");
      open.onsuccess = () => resolve(open.result);
      open.onerror = () => reject(open.error);
    });
    try {
      if (!db.objectStoreNames.contains("records")) {
        return null;
      }
      const store = db.transaction("records").objectStore("records");
      const all = (request) =>
        new Promise((resolve, reject) => {
          request.onsuccess = () => resolve(request.result);
          request.onerror = () => reject(request.error);
        });
      const [keys, values] = await Promise.all([all(store.getAllKeys()), all(store.getAll())]);
      let index = null;
      const records = {};
      for (const [i, key] of keys.entries()) {
        const value = values[i];
        if (key === "index") {
          index = typeof value === "string" ? value : null;
        } else if (value instanceof Blob) {
          records[key] = await value.text();
        } else {
          records[key] = typeof value === "string" ? value : new TextDecoder().decode(value);
        }
      }
      return { index, records };
    } finally {
      db.close();
    }
  });
}

