// Browser end-to-end test of the Swarf web build on WebGPU.
//
// Headless Chromium has no WebGPU canvas (web.test.mjs covers the WebGL2 fallback there), so this
// variant opens a headed Chromium window on $DISPLAY with WebGPU on SwiftShader's Vulkan (a CPU
// implementation that needs no GPU). `cargo xtask test` runs the e2e tests under `xvfb-run -a`;
// without a DISPLAY, or when Chromium offers no WebGPU adapter, the tests here are skipped.
//
// Environment: SWARF_WEB_DIR (default <repo>/target/web), SWARF_CHROMIUM (default
// /usr/bin/chromium), DISPLAY.

import { after, before, test } from "node:test";
import assert from "node:assert/strict";

import { BrowserSession, TEST_TIMEOUT_MS, checkPrerequisites, isError } from "./harness.mjs";

const CHROMIUM_ARGS = [
  "--enable-unsafe-webgpu",
  "--use-webgpu-adapter=swiftshader",
  "--enable-features=Vulkan",
  "--use-vulkan=swiftshader",
  "--use-angle=swiftshader",
];

let session;
let page;
/** Why the tests here cannot run, or null. */
let skipReason = null;
/** The WebGPU adapter Chromium offers, for the test log. */
let adapterInfo = null;
let ready = false;

before(async () => {
  checkPrerequisites();
  if (!process.env.DISPLAY) {
    skipReason =
      "no DISPLAY: WebGPU needs a headed Chromium on an X server (run under `xvfb-run -a`, as " +
      "`cargo xtask test` does)";
    return;
  }
  session = await BrowserSession.start({ headless: false, args: CHROMIUM_ARGS });
  page = session.page;

  // Ask for an adapter on a blank page of the test origin: WebGPU is only exposed to secure
  // contexts (127.0.0.1 is one, about:blank is not), and the app must not start yet.
  const probeUrl = `${session.baseUrl}webgpu-probe.html`;
  await page.route(probeUrl, (route) =>
    route.fulfill({ contentType: "text/html", body: "<!doctype html><title>WebGPU probe</title>" }),
  );
  await page.goto(probeUrl);
  const probe = await page.evaluate(async () => {
    if (!("gpu" in navigator)) {
      return { error: "navigator.gpu is missing" };
    }
    try {
      const adapter = await navigator.gpu.requestAdapter();
      if (adapter === null) {
        return { error: "navigator.gpu.requestAdapter() returned null" };
      }
      const { vendor, architecture, device, description } = adapter.info ?? {};
      return { info: { vendor, architecture, device, description } };
    } catch (error) {
      return { error: `navigator.gpu.requestAdapter() threw ${error}` };
    }
  });
  await page.unroute(probeUrl);
  if (probe.error) {
    skipReason = `Chromium offers no WebGPU adapter here (${probe.error})`;
  } else {
    adapterInfo = probe.info;
  }
});

after(async () => {
  await session?.close();
});

/** Skips the test when WebGPU is not available; returns whether it did. */
function skipped(t) {
  if (skipReason !== null) {
    t.skip(skipReason);
    return true;
  }
  return false;
}

test("the page gets ready on the WebGPU backend", { timeout: TEST_TIMEOUT_MS }, async (t) => {
  if (skipped(t)) {
    return;
  }
  t.diagnostic(`WebGPU adapter: ${JSON.stringify(adapterInfo)}`);
  await session.loadUntilReady("webgpu-not-ready.png");

  // egui-wgpu logs the adapter it picked ("… backend: BrowserWebGpu, device_type: Cpu …"); at
  // warn level for software adapters such as SwiftShader, at debug level (not shown) otherwise.
  const backends = session.consoleLog.filter((line) => /\bbackend: \w+/.test(line));
  assert.ok(
    backends.some((line) => line.includes("backend: BrowserWebGpu")),
    session.withLog("the console should report the wgpu adapter with `backend: BrowserWebGpu`"),
  );
  assert.ok(
    !backends.some((line) => line.includes("backend: Gl")),
    session.withLog("the app fell back to WebGL (`backend: Gl` in the console)"),
  );
  t.diagnostic(backends.find((line) => line.includes("backend: BrowserWebGpu")));

  // A canvas keeps the kind of context it was first given: `getContext("webgpu")` returns the
  // app's context, and null had the app drawn with WebGL.
  const kind = await page.evaluate(() => {
    const canvas = document.getElementById("swarf-canvas");
    return canvas.getContext("webgpu") !== null ? "webgpu" : "not webgpu";
  });
  assert.equal(kind, "webgpu", "the canvas should have a WebGPU context");

  await session.idle();
  const stats = await page.evaluate(() => window.swarf.stats());
  assert.ok(
    stats && stats.motions > 0 && stats.bounds !== null,
    `stats() of the example program should report motions > 0 and bounds: ${JSON.stringify(stats)}`,
  );
  ready = true;
});

test("the backplot canvas is not blank on WebGPU", { timeout: TEST_TIMEOUT_MS }, async (t) => {
  if (skipped(t)) {
    return;
  }
  assert.ok(ready, "the page did not get ready (see the first test)");
  await session.assertCanvasNotBlank("webgpu.png");
});

test("diagnostics report an error in the edited text", { timeout: TEST_TIMEOUT_MS }, async (t) => {
  if (skipped(t)) {
    return;
  }
  assert.ok(ready, "the page did not get ready (see the first test)");
  const broken = "G90 G21\nG00 X0 Y0 Z5\nG01 X10 Y$ F100\n";
  await page.evaluate((text) => window.swarf.setText(text), broken);
  await session.idle();
  const reported = await page.evaluate(() => window.swarf.diagnostics());
  assert.ok(
    Array.isArray(reported) && reported.some((d) => d.line === 3 && isError(d)),
    `diagnostics() should report an error on line 3 for \`Y$\`: ${JSON.stringify(reported)}`,
  );
});

test("no console errors or page errors on WebGPU", (t) => {
  if (skipped(t)) {
    return;
  }
  session.assertNoPageErrors();
});
