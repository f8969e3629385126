// Browser end-to-end test of the Swarf web build.
//
// Serves target/web/ (built by `cargo xtask web`) on 127.0.0.1, opens it in headless Chromium
// (WebGL2 through SwiftShader; headless Chromium has no WebGPU canvas, so the app falls back to
// WebGL; webgpu.test.mjs covers WebGPU) and drives the page through `window.swarf`. Run with
// `node --test tests/e2e/`, or all tests with `cargo xtask test`.
//
// Environment: SWARF_WEB_DIR (default <repo>/target/web), SWARF_CHROMIUM (default
// /usr/bin/chromium).

import { after, before, test } from "node:test";
import assert from "node:assert/strict";
import { readFile } from "node:fs/promises";

import { BrowserSession, TEST_TIMEOUT_MS, checkPrerequisites, isError } from "./harness.mjs";

const CHROMIUM_ARGS = ["--headless", "--disable-gpu", "--enable-unsafe-swiftshader"];

let session;
let page;
let exampleMotions = 0;

before(async () => {
  checkPrerequisites();
  session = await BrowserSession.start({ headless: true, args: CHROMIUM_ARGS });
  page = session.page;
});

after(async () => {
  await session?.close();
});

test("the page loads, becomes ready and shows the example program", { timeout: TEST_TIMEOUT_MS }, async () => {
  await session.loadUntilReady("not-ready.png");

  const text = await page.evaluate(() => window.swarf.getText());
  assert.equal(typeof text, "string", "getText() must return a string");
  assert.ok(text.trim().length > 0, "the editor is empty: the example program was not loaded");

  const stats = await session.eventually(
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
  await session.assertCanvasNotBlank("screenshot.png");
});

test("Ctrl+O opens a picked file in a tab", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  // Listening from the start: the browser's file chooser is intercepted only once a listener is.
  const chooserOpened = page.waitForEvent("filechooser", { timeout: 60_000 });
  // Keyboard shortcuts reach the app once the editor has the focus.
  await page.mouse.click(200, 300);
  await page.keyboard.press("Control+O");
  const chooser = await chooserOpened;
  const picked = "G90 G21\nG00 X0 Y0 Z5.\nG01 X12. F100\nM30\n";
  await chooser.setFiles({ name: "picked.nc", mimeType: "text/plain", buffer: Buffer.from(picked) });
  await session.eventually(
    () => window.swarf.getText(),
    null,
    (text) => text === picked,
    "getText() should become the picked file's text",
  );
});

test("diagnostics follow the edited text", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  const broken = "G90 G21\nG00 X0 Y0 Z5\nG01 X10 Y$ F100\n";
  await page.evaluate((text) => window.swarf.setText(text), broken);
  assert.equal(await page.evaluate(() => window.swarf.getText()), broken, "getText() after setText()");
  await session.eventually(
    () => window.swarf.diagnostics(),
    null,
    (list) => Array.isArray(list) && list.some((d) => d.line === 3 && isError(d)),
    "diagnostics() should report an error on line 3 for `Y$`",
  );

  // A square pocket outline: 2 feeds down/up and the 4 sides, all in mm.
  // Fanuc reads a number without a decimal point in 0.001 mm, so the sizes carry one.
  const square =
    "G90 G21 G17\nG00 X0 Y0 Z5.\nG01 Z-1. F100\nG01 X30.\nG01 Y20.\nG01 X0\nG01 Y0\nG00 Z5.\nM30\n";
  await page.evaluate((text) => window.swarf.setText(text), square);
  await session.eventually(
    () => window.swarf.diagnostics(),
    null,
    (list) => Array.isArray(list) && !list.some(isError),
    "diagnostics() should have no errors for a valid program",
  );
  const stats = await session.eventually(
    () => window.swarf.stats(),
    null,
    (s) => s && s.motions >= 5 && s.bounds !== null && Math.abs(s.bounds.max[0] - 30) < 1e-6,
    "stats() should report the square's motions and bounds (max X = 30)",
  );
  const near = (a, b) => Math.abs(a - b) < 1e-6;
  assert.ok(near(stats.bounds.max[1], 20), `bounds.max Y should be 20: ${JSON.stringify(stats)}`);
  assert.ok(near(stats.bounds.min[2], -1), `bounds.min Z should be -1: ${JSON.stringify(stats)}`);

  // A longer program must give more motions: stats follow every edit.
  const twice = square.replace("M30\n", "G01 Z-2.\nG01 X30.\nG01 Y20.\nG00 Z5.\nM30\n");
  await page.evaluate((text) => window.swarf.setText(text), twice);
  await session.eventually(
    () => window.swarf.stats(),
    null,
    (s) => s && s.motions > stats.motions,
    `stats().motions should grow past ${stats.motions} after adding moves`,
  );
});

test("open, select and selection", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  const program = "G90 G21\nG00 X0 Y0 Z5.\nG01 X10. F100\nM30\n";
  await page.evaluate(([name, text]) => window.swarf.open(name, text), ["part.nc", program]);
  assert.equal(await page.evaluate(() => window.swarf.getText()), program, "getText() after open()");
  await session.eventually(
    () => document.title,
    null,
    (title) => typeof title === "string" && title.startsWith("part.nc"),
    "the page title should name the opened file",
  );

  await page.evaluate(() => window.swarf.select(3));
  const expected = { start: 22, end: 35, text: "G01 X10. F100", start_line: 3, end_line: 3 };
  assert.deepEqual(await page.evaluate(() => window.swarf.selection()), expected);
  // The editor shows the selection and keeps it over the next frames.
  await session.eventually(
    () => window.swarf.selection(),
    null,
    (s) => s && s.text === expected.text && s.start_line === 3,
    "selection() should still be line 3 after the editor repainted",
  );
  // A line past the end selects the last line; nonsense is refused.
  await page.evaluate(() => window.swarf.select(999));
  const last = await page.evaluate(() => window.swarf.selection());
  assert.equal(last.start_line, 4, `select(999): ${JSON.stringify(last)}`);
  assert.equal(last.text, "M30", `select(999): ${JSON.stringify(last)}`);
  const refused = await page.evaluate(() => {
    try {
      window.swarf.select(0);
      return false;
    } catch (e) {
      return e instanceof RangeError;
    }
  });
  assert.ok(refused, "select(0) should throw a RangeError");
});

test("a file dropped on the page opens, in its encoding", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  // "(銑) G0 X7." in GB18030: the page decodes it as the desktop does.
  const bytes = [0x28, 0xe3, 0x8a, 0x29, 0x20, 0x47, 0x30, 0x20, 0x58, 0x37, 0x2e, 0x0a];
  await page.evaluate((data) => {
    const transfer = new DataTransfer();
    transfer.items.add(new File([new Uint8Array(data)], "dropped.nc"));
    const canvas = document.getElementById("swarf-canvas");
    for (const type of ["dragenter", "dragover", "drop"]) {
      canvas.dispatchEvent(
        new DragEvent(type, { dataTransfer: transfer, bubbles: true, cancelable: true }),
      );
    }
  }, bytes);
  await session.eventually(
    () => window.swarf.getText(),
    null,
    (text) => text === "(銑) G0 X7.\n",
    "getText() should become the dropped file's text",
  );
  await session.eventually(
    () => document.title,
    null,
    (title) => typeof title === "string" && title.startsWith("dropped.nc"),
    "the page title should name the dropped file",
  );
});

test("Ctrl+S downloads the program in its encoding", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");
  assert.equal(await page.evaluate(() => window.swarf.getText()), "(銑) G0 X7.\n", "after the drop test");

  // Keyboard shortcuts reach the app once the editor has the focus.
  await page.mouse.click(200, 300);
  const downloading = page.waitForEvent("download", { timeout: 30_000 });
  await page.keyboard.press("Control+S");
  const download = await downloading;
  assert.equal(download.suggestedFilename(), "dropped.nc");
  const saved = await readFile(await download.path());
  assert.deepEqual([...saved], [0x28, 0xe3, 0x8a, 0x29, 0x20, 0x47, 0x30, 0x20, 0x58, 0x37, 0x2e, 0x0a]);
});

test("unsaved edits survive a reload of the page", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  const edited = "G90 G21\nG00 X0 Y0 Z5.\nG01 X42. F100\nM30\n";
  await page.evaluate((text) => window.swarf.setText(text), edited);
  // Kept in localStorage a moment after the edit.
  await session.eventually(
    () => window.localStorage.getItem("swarf.recovery"),
    null,
    (record) => typeof record === "string" && record.includes("X42."),
    "the unsaved program should be kept in localStorage",
  );
  await session.loadUntilReady("reload-not-ready.png");
  assert.equal(
    await page.evaluate(() => window.swarf.getText()),
    edited,
    "the reloaded page should show the unsaved program",
  );
});

test("no console errors or page errors", () => {
  session.assertNoPageErrors();
});
