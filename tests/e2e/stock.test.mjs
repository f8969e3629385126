// Browser end-to-end test of the Stock view on the WebGL2 fallback (headless Chromium,
// SwiftShader) and on WebGPU (a headed Chromium on $DISPLAY, as webgpu.test.mjs; skipped without
// one or without an adapter): a real click on the backplot's Stock button has the page's worker
// cut the stock, whose findings join the diagnostics, and the view draws the cut block (its grey
// top) with the rapid into it marked red.
//
// Needs the web build (`cargo xtask web`); run with `node --test tests/e2e/stock.test.mjs`
// (under `xvfb-run -a` for the WebGPU variant).

import { before, test } from "node:test";
import assert from "node:assert/strict";

import { PNG } from "pngjs";

import { BrowserSession, TEST_TIMEOUT_MS, checkPrerequisites } from "./harness.mjs";

const WEBGL2_ARGS = ["--headless", "--disable-gpu", "--enable-unsafe-swiftshader"];
const WEBGPU_ARGS = [
  "--enable-unsafe-webgpu",
  "--use-webgpu-adapter=swiftshader",
  "--enable-features=Vulkan",
  "--use-vulkan=swiftshader",
  "--use-angle=swiftshader",
];

// A slot 2 mm deep from the top at Z0 (a 10 mm tool assumed), then a rapid down into the
// material beside it on line 7.
const PROGRAM =
  "G90 G21 G17\nG1 Z-2. F300.\nG1 X40.\nG1 Y20.\nG0 Z5.\nG0 X10. Y10.\nG0 Z-1.\nM30\n";

// The uncut top as the view shades it, and the marks of rapids into the stock (sRGB).
const TOP = [154, 156, 163];
const RAPID_MARK = [240, 40, 40];
const STOCK_CODES = ["N-STOCK-ASSUMED", "N-TOOL-ASSUMED", "W-RAPID-INTO-STOCK", "W-SHANK-CUT"];

before(() => {
  checkPrerequisites();
});

/** Pixels of the backplot within 16 of each colour of `colors`, by colour. */
async function pixels(session, colors) {
  const { page } = session;
  const view = await page.evaluate(() => window.swarf.widget("backplot"));
  assert.ok(view, "the backplot was not drawn");
  const canvas = await page.locator("#swarf-canvas").boundingBox();
  const png = PNG.sync.read(
    await page.screenshot({
      clip: { x: canvas.x + view.x, y: canvas.y + view.y, width: view.width, height: view.height },
    }),
  );
  const counts = colors.map(() => 0);
  for (let i = 0; i < png.data.length; i += 4) {
    colors.forEach((c, k) => {
      if (c.every((v, j) => Math.abs(png.data[i + j] - v) <= 16)) {
        counts[k] += 1;
      }
    });
  }
  return counts;
}

/** The Stock button's checks on the page `session` has loaded; `artifact` names its screenshot. */
async function checkStockView(session, artifact) {
  const { page } = session;
  await page.evaluate((text) => window.swarf.setText(text), PROGRAM);
  await session.idle();
  const before = await page.evaluate(() => window.swarf.diagnostics());
  assert.deepEqual(before.filter((d) => STOCK_CODES.includes(d.code)), [], "stock findings before");
  const [topBefore] = await pixels(session, [TOP]);

  const button = await page.evaluate(() => window.swarf.widget("stock"));
  assert.ok(button, "the Stock button was not drawn");
  const canvas = await page.locator("#swarf-canvas").boundingBox();
  await page.mouse.click(
    canvas.x + button.x + button.width / 2,
    canvas.y + button.y + button.height / 2,
  );

  const found = await session.eventually(
    () => window.swarf.diagnostics(),
    null,
    (list) => list.some((d) => d.code === "W-RAPID-INTO-STOCK"),
    "the rapid into the stock should join the diagnostics once the Stock button is on",
    60_000,
  );
  assert.deepEqual(
    found.filter((d) => STOCK_CODES.includes(d.code)).map((d) => [d.line, d.code]),
    [
      [2, "N-TOOL-ASSUMED"],
      [2, "N-STOCK-ASSUMED"],
      [7, "W-RAPID-INTO-STOCK"],
    ],
  );

  // The cut block is drawn (its grey top fills much of the view), the rapid marked red.
  let counts;
  const deadline = Date.now() + 30_000;
  do {
    await page.waitForTimeout(300);
    counts = await pixels(session, [TOP, RAPID_MARK]);
  } while ((counts[0] < topBefore + 2000 || counts[1] < 20) && Date.now() < deadline);
  const [top, red] = counts;
  if (top < topBefore + 2000 || red < 20) {
    await session.saveFailureScreenshot(artifact);
  }
  assert.ok(top > topBefore + 2000, session.withLog(`the stock's top: ${topBefore} → ${top} px`));
  assert.ok(red >= 20, session.withLog(`the rapid into the stock: ${red} red px`));
  session.assertNoPageErrors();
}

test("the Stock button cuts, draws and reports the stock on WebGL2", { timeout: TEST_TIMEOUT_MS }, async () => {
  const session = await BrowserSession.start({ headless: true, args: WEBGL2_ARGS });
  try {
    await session.loadUntilReady("stock-webgl2-not-ready.png");
    await checkStockView(session, "stock-webgl2.png");
  } finally {
    await session.close();
  }
});

test("the Stock button cuts, draws and reports the stock on WebGPU", { timeout: TEST_TIMEOUT_MS }, async (t) => {
  if (!process.env.DISPLAY) {
    t.skip("no DISPLAY: WebGPU needs a headed Chromium on an X server (run under `xvfb-run -a`)");
    return;
  }
  const session = await BrowserSession.start({ headless: false, args: WEBGPU_ARGS });
  try {
    await session.loadUntilReady("stock-webgpu-not-ready.png");
    // egui-wgpu logs the adapter it picked (see webgpu.test.mjs).
    if (!session.consoleLog.some((line) => line.includes("backend: BrowserWebGpu"))) {
      t.skip("Chromium offers no WebGPU adapter here: the page runs on WebGL2");
      return;
    }
    await checkStockView(session, "stock-webgpu.png");
  } finally {
    await session.close();
  }
});
