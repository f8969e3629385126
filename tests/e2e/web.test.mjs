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

import {
  BrowserSession,
  TEST_TIMEOUT_MS,
  checkPrerequisites,
  isError,
  rasterProgram,
  recoveryRecords,
} from "./harness.mjs";

const CHROMIUM_ARGS = ["--headless", "--disable-gpu", "--enable-unsafe-swiftshader"];

let session;
let page;
let exampleMotions = 0;

before(async () => {
  checkPrerequisites();
  session = await BrowserSession.start({ headless: true, args: CHROMIUM_ARGS });
  page = session.page;
  // From the start, long before the first Ctrl+O (see interceptFileChoosers).
  session.interceptFileChoosers();
  // The GLSL each WebGL shader is compiled from, as the page hands it over.
  await page.addInitScript(() => {
    const context = WebGL2RenderingContext.prototype;
    const shaderSource = context.shaderSource;
    window.swarfTestShaders = [];
    context.shaderSource = function (shader, source) {
      window.swarfTestShaders.push(source);
      return shaderSource.call(this, shader, source);
    };
  });
});

// "(銑) G0 X7." in GB18030.
const GB18030_PROGRAM = [0x28, 0xe3, 0x8a, 0x29, 0x20, 0x47, 0x30, 0x20, 0x58, 0x37, 0x2e, 0x0a];

/**
 * Runs `body` with the File System Access API's pickers hidden, as in a browser without them
 * (Firefox, Safari): Open then shows the file input and Save downloads.
 */
async function withoutFileSystemAccess(body) {
  await page.evaluate(() => {
    window.swarfTestPickers = [window.showOpenFilePicker, window.showSaveFilePicker];
    window.showOpenFilePicker = undefined;
    window.showSaveFilePicker = undefined;
  });
  try {
    await body();
  } finally {
    await page.evaluate(() => {
      [window.showOpenFilePicker, window.showSaveFilePicker] = window.swarfTestPickers;
    });
  }
}

/** Ctrl+O, a program picked in the file input, and its text in the editor. */
async function openWithFileInput(name, text) {
  await withoutFileSystemAccess(async () => {
    const chooserOpened = session.nextFileChooser(60_000);
    // Keyboard shortcuts reach the app once the editor has the focus.
    await page.mouse.click(200, 300);
    await page.keyboard.press("Control+O");
    const chooser = await chooserOpened;
    await chooser.setFiles({ name, mimeType: "text/plain", buffer: Buffer.from(text) });
  });
  await session.eventually(
    () => window.swarf.getText(),
    null,
    (got) => got === text,
    `getText() should become the text of ${name}, picked after Ctrl+O`,
  );
  await session.eventually(
    () => document.title,
    null,
    (title) => typeof title === "string" && title.startsWith(name),
    `the page title should name ${name}`,
  );
}

after(async () => {
  await session?.close();
});

test("the page loads, becomes ready and shows the example program", { timeout: TEST_TIMEOUT_MS }, async () => {
  await session.loadUntilReady("not-ready.png");

  const text = await page.evaluate(() => window.swarf.getText());
  assert.equal(typeof text, "string", "getText() must return a string");
  assert.ok(text.trim().length > 0, "the editor is empty: the example program was not loaded");

  await session.idle();
  const stats = await page.evaluate(() => window.swarf.stats());
  assert.ok(
    stats && stats.motions > 0 && stats.bounds !== null,
    `stats() of the example program should report motions > 0 and bounds: ${JSON.stringify(stats)}`,
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

test("egui's shader reaches WebGL without its software texture filtering", { timeout: TEST_TIMEOUT_MS }, async () => {
  const shaders = await page.evaluate(() => window.swarfTestShaders);
  const egui = shaders.filter((source) => /uint predictable_texture_filtering;/.test(source));
  assert.ok(egui.length > 0, "no WebGL shader declares egui's predictable_texture_filtering");
  const reads = shaders.filter((source) => /\.predictable_texture_filtering\b/.test(source));
  assert.deepEqual(reads, [], "a WebGL shader still reads predictable_texture_filtering");
});

test("the canvas's WebGL2 context is opaque and has no depth buffer", { timeout: TEST_TIMEOUT_MS }, async () => {
  const attributes = await page.evaluate(() =>
    document.getElementById("swarf-canvas").getContext("webgl2").getContextAttributes(),
  );
  assert.equal(attributes.alpha, false, "the canvas is blended into the page each frame");
  assert.equal(attributes.depth, false, "the canvas keeps a depth buffer nothing draws into");
});

test("the backplot canvas is not blank", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");
  await session.assertCanvasNotBlank("screenshot.png");
});

test("Ctrl+O opens a file picked in the file input in a tab", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");
  await openWithFileInput("picked.nc", "G90 G21\nG00 X0 Y0 Z5.\nG01 X12. F100\nM30\n");
});

test("diagnostics follow the edited text", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  const broken = "G90 G21\nG00 X0 Y0 Z5\nG01 X10 Y$ F100\n";
  await page.evaluate((text) => window.swarf.setText(text), broken);
  assert.equal(await page.evaluate(() => window.swarf.getText()), broken, "getText() after setText()");
  await session.idle();
  const reported = await page.evaluate(() => window.swarf.diagnostics());
  assert.ok(
    Array.isArray(reported) && reported.some((d) => d.line === 3 && isError(d)),
    `diagnostics() should report an error on line 3 for \`Y$\`: ${JSON.stringify(reported)}`,
  );

  // A square pocket outline: 2 feeds down/up and the 4 sides, all in mm.
  // Fanuc reads a number without a decimal point in 0.001 mm, so the sizes carry one.
  const square =
    "G90 G21 G17\nG00 X0 Y0 Z5.\nG01 Z-1. F100\nG01 X30.\nG01 Y20.\nG01 X0\nG01 Y0\nG00 Z5.\nM30\n";
  await page.evaluate((text) => window.swarf.setText(text), square);
  await session.idle();
  const clean = await page.evaluate(() => window.swarf.diagnostics());
  assert.ok(
    Array.isArray(clean) && !clean.some(isError),
    `diagnostics() should have no errors for a valid program: ${JSON.stringify(clean)}`,
  );
  const stats = await page.evaluate(() => window.swarf.stats());
  assert.ok(
    stats && stats.motions >= 5 && stats.bounds !== null && Math.abs(stats.bounds.max[0] - 30) < 1e-6,
    `stats() should report the square's motions and bounds (max X = 30): ${JSON.stringify(stats)}`,
  );
  const near = (a, b) => Math.abs(a - b) < 1e-6;
  assert.ok(near(stats.bounds.max[1], 20), `bounds.max Y should be 20: ${JSON.stringify(stats)}`);
  assert.ok(near(stats.bounds.min[2], -1), `bounds.min Z should be -1: ${JSON.stringify(stats)}`);

  // A longer program must give more motions: stats follow every edit.
  const twice = square.replace("M30\n", "G01 Z-2.\nG01 X30.\nG01 Y20.\nG00 Z5.\nM30\n");
  await page.evaluate((text) => window.swarf.setText(text), twice);
  await session.idle();
  const grown = await page.evaluate(() => window.swarf.stats());
  assert.ok(
    grown.motions > stats.motions,
    `stats().motions should grow past ${stats.motions} after adding moves: ${JSON.stringify(grown)}`,
  );
});

test("diagnostics() and stats() report what the page shows; idle() waits for the current text", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  const short = "G90 G21\nG00 X0 Y0 Z5.\nG01 X10. F100\nM30\n";
  await page.evaluate((text) => window.swarf.setText(text), short);
  await session.idle();
  // What the page shows, without the wasm memories' sizes, which change as it runs.
  const shown = await page.evaluate(() => ({ ...window.swarf.stats(), wasm_bytes: undefined }));
  assert.equal(shown.blocks, 4, `stats() of the short program: ${JSON.stringify(shown)}`);

  // A long program with an error on its last line: its analysis takes several frames.
  const lines = ["G90 G21 G17", "G00 X0 Y0 Z5.", "G01 Z-1. F1000"];
  for (let i = 0; i < 60_000; i++) {
    lines.push(`X${i % 97}. Y${i % 89}.`);
  }
  lines.push("G01 X10 Y$ F100", "M30", "");
  const long = lines.join("\n");
  const rightAfter = await page.evaluate((text) => {
    window.swarf.setText(text);
    const stats = { ...window.swarf.stats(), wasm_bytes: undefined };
    return { stats, diagnostics: window.swarf.diagnostics() };
  }, long);
  assert.deepEqual(rightAfter.stats, shown, "right after setText(), stats() reports the analysis on screen");
  assert.ok(
    !rightAfter.diagnostics.some(isError),
    `right after setText(), diagnostics() reports the analysis on screen: ${JSON.stringify(rightAfter.diagnostics)}`,
  );
  await session.idle();
  const stats = await page.evaluate(() => window.swarf.stats());
  assert.ok(stats.blocks > 60_000 && stats.motions > 60_000, `stats() after idle(): ${JSON.stringify(stats)}`);
  const reported = await page.evaluate(() => window.swarf.diagnostics());
  assert.ok(
    reported.some((d) => d.line === lines.length - 2 && isError(d)),
    `diagnostics() after idle() should report the last lines' error: ${JSON.stringify(reported.slice(0, 5))}`,
  );
  await page.evaluate((text) => window.swarf.setText(text), short);
  await session.idle();
  assert.deepEqual(
    await page.evaluate(() => ({ ...window.swarf.stats(), wasm_bytes: undefined })),
    shown,
    "stats() of the short program again",
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

test("a call reaches the program of another tab as it is now, after edits in either tab", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  const sub = (x) => `O1234\nG01 X${x}. Y0 F100\nM99\n`;
  const main = "G90 G21\nG00 X0 Y0 Z5.\nM98 P1234\nM30\n";
  await page.evaluate(([name, text]) => window.swarf.open(name, text), ["O1234.nc", sub(50)]);
  await page.evaluate(([name, text]) => window.swarf.open(name, text), ["main.nc", main]);
  // 1-based, as the tab strip's widgets are named.
  const subTab = await page.evaluate(() => window.swarf.tabs().tabs.findIndex((t) => t.name === "O1234.nc") + 1);
  assert.equal(await page.evaluate(() => window.swarf.tabs().active + 1), subTab + 1, "main.nc is shown");
  const farthest = async () => {
    await session.idle();
    return page.evaluate(() => window.swarf.stats().bounds?.max[0]);
  };
  assert.equal(await farthest(), 50, "the call should run the other tab's program");
  // An edit of the calling program: the other tab's text, unchanged, is not sent to the worker
  // again, and the call still reaches it.
  await page.evaluate((text) => window.swarf.setText(text), main.replace("M30", "G00 X1.\nM30"));
  assert.equal(await farthest(), 50, "the call should reach the other tab after an edit of its own");
  // An edit in the called program's tab, seen from the calling one.
  const showTab = async (n, text) => {
    // The strip scrolled to its end by the wheel, as far as the tab's place stays put.
    const strip = await page.evaluate(() => {
      const shown = Array.from({ length: 99 }, (_, i) => window.swarf.widget(`tab ${i + 1}`));
      return shown.find((r) => r !== null);
    });
    await page.mouse.move(strip.x + strip.width / 2, strip.y + strip.height / 2);
    await page.mouse.wheel(1000, 0);
    let [rect, before] = [null, undefined];
    for (let i = 0; i < 50 && (rect === null || JSON.stringify(rect) !== JSON.stringify(before)); i++) {
      before = rect;
      await page.waitForTimeout(200);
      rect = await page.evaluate((i) => window.swarf.widget(`tab ${i}`), n);
    }
    assert.ok(rect !== null, `tab ${n} should come in sight`);
    const [x, y] = [rect.x + rect.width / 2, rect.y + rect.height / 2];
    await page.mouse.move(x, y, { steps: 5 });
    await page.waitForTimeout(100);
    await page.mouse.click(x, y, { delay: 50 });
    await session.eventually(() => window.swarf.getText(), null, (t) => t === text, `tab ${n} should be shown`);
  };
  await showTab(subTab, sub(50));
  await page.evaluate((text) => window.swarf.setText(text), sub(70));
  await showTab(subTab + 1, main.replace("M30", "G00 X1.\nM30"));
  assert.equal(await farthest(), 70, "the call should run the other tab's program as edited");
});

test("a file dropped on the page opens, in its encoding", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  // GB18030: the page decodes it as the desktop does.
  const bytes = GB18030_PROGRAM;
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

  await withoutFileSystemAccess(async () => {
    // Keyboard shortcuts reach the app once the editor has the focus.
    await page.mouse.click(200, 300);
    const downloading = page.waitForEvent("download", { timeout: 30_000 });
    await page.keyboard.press("Control+S");
    const download = await downloading;
    assert.equal(download.suggestedFilename(), "dropped.nc");
    const saved = await readFile(await download.path());
    assert.deepEqual([...saved], GB18030_PROGRAM);
  });
});

test("Ctrl+O still opens the file input after open, select, a drop and Ctrl+S", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");
  await openWithFileInput("late.nc", "G90 G21\nG00 X0 Y0 Z5.\nG01 Y7. F100\nM30\n");
});

test("a click in the backplot selects the segment's line", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  // Two feed moves far apart at Z-1: line 4 along X, line 5 along Y.
  const program =
    "G90 G21 G17\nG00 X0 Y0 Z5.\nG01 Z-1. F100\nG01 X40.\nG01 Y30.\nG00 Z5.\nM30\n";
  await page.evaluate(([name, text]) => window.swarf.open(name, text), ["pick.nc", program]);
  await session.idle();
  const opened = await page.evaluate(() => window.swarf.stats());
  assert.ok(
    opened.bounds !== null && Math.abs(opened.bounds.max[0] - 40) < 1e-6,
    `stats() should describe the opened program (max X = 40): ${JSON.stringify(opened)}`,
  );
  const canvas = await page.locator("#swarf-canvas").boundingBox();
  for (const [line, midpoint] of [
    [4, [20, 0, -1]],
    [5, [40, 15, -1]],
  ]) {
    // The view fits the new program over the next frames: wait until the point stays put.
    let previous = null;
    const at = await session.eventually(
      (p) => window.swarf.project(p),
      midpoint,
      (xy) => {
        const steady =
          xy !== null && previous !== null && Math.hypot(xy[0] - previous[0], xy[1] - previous[1]) < 0.5;
        previous = xy;
        return steady;
      },
      `project(${JSON.stringify(midpoint)}) should give a steady point in the backplot`,
    );
    await page.waitForTimeout(300);
    assert.ok(
      at[0] > canvas.x && at[0] < canvas.x + canvas.width && at[1] > canvas.y && at[1] < canvas.y + canvas.height,
      `line ${line}'s midpoint ${JSON.stringify(midpoint)} is drawn at ${JSON.stringify(at)}, outside the canvas`,
    );
    await page.mouse.click(at[0], at[1]);
    await session.eventually(
      () => window.swarf.selection(),
      null,
      (s) => s && s.start_line === line,
      `a click on line ${line}'s segment at ${JSON.stringify(at.map(Math.round))} should select line ${line}`,
    );
  }
  const refused = await page.evaluate(() => {
    try {
      window.swarf.project([1, 2]);
      return false;
    } catch (e) {
      return e instanceof TypeError;
    }
  });
  assert.ok(refused, "project([1, 2]) should throw a TypeError");
});

test("the wheel zooms into a dense path, drawn finer once the worker simplifies it again", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");
  // Rows of 200 feeds: far more moves than the fitted view can show apart.
  await page.evaluate(([name, text]) => window.swarf.open(name, text), ["dense.nc", rasterProgram(40_000, 200)]);
  await session.idle();
  const fitted = await page.evaluate(() => window.swarf.stats());
  assert.ok(
    fitted.drawn_points !== null && fitted.drawn_points > 1 && fitted.drawn_points < fitted.motions / 4,
    `the fitted view should draw the path simplified: ${JSON.stringify(fitted)}`,
  );
  const view = await page.evaluate(() => window.swarf.widget("backplot"));
  await page.mouse.move(view.x + view.width / 2, view.y + view.height / 2);
  for (let i = 0; i < 8; i++) {
    await page.mouse.wheel(0, -240);
    await page.waitForTimeout(50);
  }
  const finer = await session.eventually(
    () => window.swarf.stats().drawn_points,
    null,
    (drawn) => drawn > fitted.drawn_points,
    `zoomed in, the path should be drawn with more of its points than the ${fitted.drawn_points} fitted`,
  );
  assert.ok(finer <= fitted.motions + 1, `${finer} points drawn of ${fitted.motions + 1}`);
});

test("idle() resolves once a path too dense for one frame is drawn whole", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");
  // 2,000 rows of 400 feeds: the fitted view draws some 12,000 segments, which take several
  // frames (`FRAME_WORK` a frame) while the last picture stays on screen.
  await page.evaluate(([name, text]) => window.swarf.open(name, text), ["rows.nc", rasterProgram(800_000, 400)]);
  // What the page says the moment idle() resolves, in the same task.
  const atIdle = await page.evaluate(async () => {
    await window.swarf.idle();
    return window.swarf.stats();
  });
  assert.ok(
    atIdle.drawn_points > 6 * 2048,
    `the fitted view should take several frames to draw: ${atIdle.drawn_points} points`,
  );
  assert.equal(atIdle.drawing, false, "idle() came before the picture was whole");
  // And nothing in the view changes after it.
  const clip = await page.evaluate(() => window.swarf.widget("backplot"));
  const shown = await page.screenshot({ clip });
  await page.waitForTimeout(1000);
  assert.ok(shown.equals(await page.screenshot({ clip })), "the view changed after idle()");
});

test("with the File System Access API, Save writes back to the opened file in its encoding", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  // Pickers handing out handles whose writes are recorded (Playwright cannot answer the
  // real ones).
  await page.evaluate((opened) => {
    const record = { opens: [], saves: [], writes: [] };
    window.swarfFsa = record;
    const handle = (name, bytes) => ({
      kind: "file",
      name,
      async isSameEntry(other) {
        return other === this;
      },
      async getFile() {
        return new File([new Uint8Array(bytes)], name);
      },
      async createWritable() {
        const chunks = [];
        return {
          async write(data) {
            chunks.push(...new Uint8Array(data));
          },
          async close() {
            record.writes.push({ name, bytes: chunks });
          },
        };
      },
    });
    // The same file each time.
    const gbk = handle("gbk.nc", opened);
    window.showOpenFilePicker = async (options) => {
      record.opens.push(JSON.parse(JSON.stringify(options ?? null)));
      return [gbk];
    };
    window.showSaveFilePicker = async (options) => {
      record.saves.push(JSON.parse(JSON.stringify(options ?? null)));
      return handle("saved-as.nc", []);
    };
  }, GB18030_PROGRAM);
  const record = () => page.evaluate(() => window.swarfFsa);
  const titled = (prefix, what) =>
    session.eventually(
      () => document.title,
      null,
      (title) => typeof title === "string" && title.startsWith(prefix),
      what,
    );

  // Open: the picker's file, decoded.
  await page.mouse.click(200, 300);
  await page.keyboard.press("Control+O");
  await session.eventually(
    () => window.swarf.getText(),
    null,
    (text) => text === "(銑) G0 X7.\n",
    "getText() should become the text of the file the open picker gave",
  );
  await titled("gbk.nc —", "the page title should name gbk.nc, with nothing unsaved");
  const opens = (await record()).opens;
  assert.equal(opens.length, 1, "showOpenFilePicker should be called once");
  assert.ok(
    opens[0].types?.[0]?.accept?.["text/plain"]?.includes(".nc"),
    `showOpenFilePicker should offer .nc files: ${JSON.stringify(opens[0])}`,
  );

  // Save: written back to the same handle, in GB18030, without asking.
  await page.evaluate(() => window.swarf.setText("(銑) G0 X8.\n"));
  await titled("gbk.nc* —", "the edit should leave unsaved changes");
  await page.mouse.click(200, 300);
  await page.keyboard.press("Control+S");
  await titled("gbk.nc —", "Ctrl+S should save gbk.nc");
  let now = await record();
  assert.deepEqual(now.writes, [
    { name: "gbk.nc", bytes: [0x28, 0xe3, 0x8a, 0x29, 0x20, 0x47, 0x30, 0x20, 0x58, 0x38, 0x2e, 0x0a] },
  ]);
  assert.equal(now.saves.length, 0, "Save of an opened file should not ask for a file");

  // Opening the same file again brings its tab back, unsaved changes and all.
  const unsaved = "(銑) G0 X8.\nG0 Y1.\n";
  await page.evaluate((text) => window.swarf.setText(text), unsaved);
  await page.evaluate(() => window.swarf.open("other.nc", "G0 X1.\n"));
  await titled("other.nc —", "open() should show other.nc");
  await page.mouse.click(200, 300);
  await page.keyboard.press("Control+O");
  await titled("gbk.nc* —", "opening gbk.nc again should bring back its tab");
  assert.equal(await page.evaluate(() => window.swarf.getText()), unsaved, "the tab keeps its unsaved text");
  assert.equal((await record()).opens.length, 2, "showOpenFilePicker should be called again");

  // Save As: asks, suggesting the current name, and the tab becomes the new file.
  await page.evaluate(() => window.swarf.setText("(銑) G0 X9.\n"));
  await titled("gbk.nc* —", "the edit should leave unsaved changes");
  await page.mouse.click(200, 300);
  await page.keyboard.press("Control+Shift+S");
  await titled("saved-as.nc —", "Save As should name the tab after the new file");
  now = await record();
  assert.deepEqual(now.saves, [{ suggestedName: "gbk.nc" }]);
  assert.deepEqual(now.writes[1], {
    name: "saved-as.nc",
    bytes: [0x28, 0xe3, 0x8a, 0x29, 0x20, 0x47, 0x30, 0x20, 0x58, 0x39, 0x2e, 0x0a],
  });

  // A cancelled picker: nothing written, the changes stay unsaved, no error.
  await page.evaluate(() => {
    window.showSaveFilePicker = async () => {
      window.swarfFsa.saves.push("cancelled");
      throw new DOMException("The user aborted a request.", "AbortError");
    };
    window.swarf.setText("G0 X10.\n");
  });
  await titled("saved-as.nc* —", "the edit should leave unsaved changes");
  await page.mouse.click(200, 300);
  await page.keyboard.press("Control+Shift+S");
  await session.eventually(
    () => window.swarfFsa.saves.length,
    null,
    (n) => n === 2,
    "Save As should ask the (cancelling) picker",
  );
  await page.waitForTimeout(500);
  now = await record();
  assert.equal(now.writes.length, 2, "a cancelled Save As should write nothing");
  assert.ok((await page.title()).startsWith("saved-as.nc* —"), "the changes should stay unsaved");
});

test("unsaved edits survive a reload of the page", { timeout: TEST_TIMEOUT_MS }, async () => {
  assert.ok(exampleMotions > 0, "the page did not get ready (see the first test)");

  const edited = "G90 G21\nG00 X0 Y0 Z5.\nG01 X42. F100\nM30\n";
  await page.evaluate((text) => window.swarf.setText(text), edited);
  // Kept in IndexedDB a moment after the edit: a record a tab, then the index naming the
  // active tab's record (a reload before the index is written finds the round before).
  const activeRecord = (stored) => {
    const [head, ...tabs] = (stored?.index ?? "").split("\n");
    const active = Number(head.split("\t")[2]);
    return stored?.records[tabs[active]?.split("\t")[2]] ?? "";
  };
  for (let waited = 0; ; waited += 250) {
    if (activeRecord(await recoveryRecords(page)).includes("X42.")) {
      break;
    }
    assert.ok(waited < 30_000, "the unsaved program should be kept in IndexedDB within 30 s");
    await page.waitForTimeout(250);
  }
  await session.loadUntilReady("reload-not-ready.png");
  // The tabs come back from IndexedDB, which the page reads after its first frame.
  await session.eventually(
    () => window.swarf.getText(),
    null,
    (text) => text === edited,
    "the reloaded page should show the unsaved program",
  );
});

test("no console errors or page errors", () => {
  session.assertNoPageErrors();
});
