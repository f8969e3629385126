// Web benchmark (not a test): load-to-first-frame of the page from a cold cache, served by
// `cargo xtask serve`, the wasm's size as sent and on disk, then a generated 1M-line
// surfacing program handed to the editor through `window.swarf.open`, timed until
// `window.swarf.idle()` resolves: its analysis finished in the page's worker, as for a person,
// and a frame showing it painted, with the longest gap between frames meanwhile against the
// longest while the empty page repaints; and before it, the same keystroke in a 20-line and in
// a 10,000-line program, timed the same way; the page and worker's memory with the long program
// open (with the two wasm memories and the page's JavaScript heap apart, again once the page's
// garbage is collected, and in a fresh page that opened it as a file with Ctrl+O), and npm's
// gcode-preview given it in the same browser (`peer.mjs`). Headless Chromium (WebGL2 through
// SwiftShader).
// Build first with `cargo xtask web`, then run:
//   node tests/e2e/bench-web.mjs [LINES]        (default 1000000)
// Prints a Markdown table row per figure.

import { readFileSync, rmSync, writeFileSync } from "node:fs";
import { stat } from "node:fs/promises";
import { tmpdir } from "node:os";
import path from "node:path";

import { execFileSync } from "node:child_process";

import { BrowserSession, SITE } from "./harness.mjs";
import { gcodePreviewMs } from "./peer.mjs";

const lines = Number(process.argv[2] ?? 1_000_000);
/** Keystrokes timed in each program: frames take 0.1–0.3 s under SwiftShader, so a median
 * of several keeps the ratio of the two programs steady. */
const KEYSTROKES = 11;

/** The same surfacing program as crates/syntax/benches/surfacing.rs, `lines` moves long. */
function surfacing(count) {
  const out = ["%", "O1000 (SURFACING)", "G90 G21 G17 G54", "G00 X0. Y0. Z5.", "G01 Z0. F1500."];
  for (let n = 0; n < count; n++) {
    const x = (n % 400) * 0.25;
    const y = Math.floor(n / 400) * 0.5;
    const z = -Math.abs(Math.sin(x * 0.07) * Math.cos(y * 0.05)) * 3.0;
    out.push(`N${(n % 99999) + 1} G01 X${x.toFixed(3)} Y${y.toFixed(3)} Z${z.toFixed(4)}`);
  }
  out.push("M30", "%", "");
  return out.join("\n");
}

/**
 * Median milliseconds of `times` keystrokes in a `count`-move program, each timed from the key
 * to `idle()` resolving (the new text's analysis finished and a frame showing it painted): `$`
 * typed at the start of line 3 (an error in), then Backspace (out again), and so on.
 */
async function keystroke(session, count, times) {
  const { page } = session;
  await page.evaluate((program) => window.swarf.open("keys.nc", program), surfacing(count));
  await session.idle();
  const editor = await page.evaluate(() => window.swarf.widget("editor"));
  await page.mouse.click(editor.x + editor.width / 2, editor.y + editor.height / 2);
  await page.evaluate(() => window.swarf.select(3));
  await page.keyboard.press("ArrowLeft");
  await session.idle();
  const samples = [];
  for (let i = 0; i < times; i++) {
    const t0 = performance.now();
    await page.keyboard.press(i % 2 === 0 ? "$" : "Backspace");
    await session.idle();
    samples.push(performance.now() - t0);
    const marked = await page.evaluate(() =>
      window.swarf.diagnostics().some((d) => d.line === 3 && d.code === "E-SYNTAX-CHAR"),
    );
    if (marked !== (i % 2 === 0)) {
      throw new Error(`keystroke ${i + 1}: line 3's error is ${marked ? "shown" : "not shown"}`);
    }
  }
  samples.sort((a, b) => a - b);
  return samples[Math.floor(times / 2)];
}

/** Starts recording the times of the page's frames (`requestAnimationFrame` callbacks). */
function recordFrames(page) {
  return page.evaluate(() => {
    window.benchFrames = [];
    const frame = (now) => {
      window.benchFrames.push(now);
      requestAnimationFrame(frame);
    };
    requestAnimationFrame(frame);
  });
}

/**
 * The gaps in milliseconds between the frames recorded since the last call, from page time
 * `after` on (and from `after` to the first of them).
 */
function frameGaps(page, after = 0) {
  return page.evaluate((after) => {
    const times = window.benchFrames.splice(0).filter((t) => t >= after);
    const from = after > 0 ? [after, ...times] : times;
    return from.slice(1).map((t, i) => t - from[i]);
  }, after);
}

/** The longest gap between frames while the pointer moves over the empty page's view. */
async function emptyPageGap(session) {
  const { page } = session;
  const view = await page.evaluate(() => window.swarf.widget("backplot"));
  await frameGaps(page);
  for (let i = 0; i < 40; i++) {
    await page.mouse.move(view.x + view.width * (0.2 + i / 80), view.y + view.height / 2);
    await page.waitForTimeout(40);
  }
  const gaps = await frameGaps(page);
  return Math.max(...gaps);
}

/**
 * Megabytes of the page's renderer process, which runs the page and its analysis worker (a
 * dedicated worker is a thread of its page's renderer): resident, and private (its own pages,
 * without the browser's code it shares with the other processes, as Chromium's task manager
 * counts a process's footprint). The session's other renderers (the spare one Chromium keeps
 * ready, the service worker's) are left out: the page's is the largest, holding both wasm
 * memories.
 */
function rendererMb(session) {
  const ps = execFileSync("ps", ["-eo", "pid=,rss=,args="], { encoding: "utf8", maxBuffer: 1 << 26 });
  const [pid, rssKb] = ps
    .split("\n")
    .filter((l) => l.includes("--type=renderer") && l.includes(session.userDataDir))
    .map((l) => l.trim().split(/\s+/).slice(0, 2).map(Number))
    .reduce((a, b) => (b[1] > a[1] ? b : a), [0, 0]);
  const rollup = readFileSync(`/proc/${pid}/smaps_rollup`, "utf8");
  const privateKb = [...rollup.matchAll(/^Private_(?:Clean|Dirty):\s+(\d+)/gm)].reduce(
    (sum, m) => sum + Number(m[1]),
    0,
  );
  return { resident: rssKb / 1024, private: privateKb / 1024 };
}

/**
 * The page's renderer process with `text` opened as a person opens a file, in a fresh page:
 * Ctrl+O and the file picked in the file input (the page then holds no caller's string).
 */
async function pickedFileMb(text) {
  const file = path.join(tmpdir(), `swarf-bench-${process.pid}.nc`);
  writeFileSync(file, text);
  const session = await BrowserSession.start({ headless: true, args: BROWSER_ARGS });
  try {
    session.interceptFileChoosers();
    await session.loadUntilReady("bench-not-ready.png");
    const { page } = session;
    // As in a browser without the File System Access API: Ctrl+O opens the file input.
    await page.evaluate(() => {
      window.showOpenFilePicker = undefined;
    });
    const chooser = session.nextFileChooser(60_000);
    const editor = await page.evaluate(() => window.swarf.widget("editor"));
    await page.mouse.click(editor.x + editor.width / 2, editor.y + editor.height / 2);
    await page.keyboard.press("Control+O");
    await (await chooser).setFiles(file);
    await session.eventually(
      () => window.swarf.stats().motions,
      null,
      (motions) => motions >= lines,
      "the picked program's moves should all be shown",
      120_000,
    );
    await session.idle();
    return rendererMb(session);
  } finally {
    await session.close();
    rmSync(file, { force: true });
  }
}

const BROWSER_ARGS = ["--headless", "--disable-gpu", "--enable-unsafe-swiftshader", "--enable-precise-memory-info"];
const session = await BrowserSession.start({
  headless: true,
  args: BROWSER_ARGS,
});
try {
  const wasm = session.page.waitForResponse((r) => r.url().endsWith("/swarf_app_bg.wasm"));
  const started = Date.now();
  await session.loadUntilReady("bench-not-ready.png");
  const ready = Date.now() - started;
  const wasmResponse = await wasm;
  await wasmResponse.finished();
  const sent = (await wasmResponse.request().sizes()).responseBodySize;
  const encoding = wasmResponse.headers()["content-encoding"] ?? "identity";
  const onDisk = async (suffix) => (await stat(path.join(SITE, `swarf_app_bg.wasm${suffix}`))).size;
  const wasmSizes = [sent, await onDisk(".gz"), await onDisk("")].map((b) => (b / 1e6).toFixed(2));
  // The service worker stores the page's files once, after the first load: measured after it.
  await session.page.evaluate(() => navigator.serviceWorker?.ready);
  await recordFrames(session.page);
  const emptyGap = await emptyPageGap(session);
  const emptyMb = rendererMb(session);
  const shortKeyMs = await keystroke(session, 20, KEYSTROKES);
  const keyMs = await keystroke(session, 10_000, KEYSTROKES);
  const text = surfacing(lines);
  await frameGaps(session.page);
  const result = await session.page.evaluate(async ([name, program]) => {
    const t0 = performance.now();
    window.swarf.open(name, program);
    const opened = performance.now();
    const late = new Promise((resolve) => setTimeout(() => resolve("late"), 600_000));
    if ((await Promise.race([window.swarf.idle(), late])) === "late") {
      return { ms: -1, opened, call: opened - t0, motions: window.swarf.stats().motions };
    }
    const ms = performance.now() - t0;
    return { ms, opened, call: opened - t0, motions: window.swarf.stats().motions };
  }, ["surfacing.nc", text]);
  const openGap = Math.max(...(await frameGaps(session.page, result.opened)));
  const memoryMb = rendererMb(session);
  const parts = await session.page.evaluate(() => ({
    ...window.swarf.stats().wasm_bytes,
    js: performance.memory.usedJSHeapSize,
  }));
  const partsMb = [parts.page, parts.worker, parts.js].map((b) => Math.round(b / 2 ** 20));
  // The page's garbage (the text as the caller's string, its copies on the way in) collected.
  const cdp = await session.page.context().newCDPSession(session.page);
  await cdp.send("HeapProfiler.collectGarbage");
  await session.page.waitForTimeout(1000);
  const collectedMb = rendererMb(session);
  const collectedJs = await session.page.evaluate(() => performance.memory.usedJSHeapSize);
  const peerMs = await gcodePreviewMs(session.context, text);
  const pickedMb = await pickedFileMb(text);
  if (result.ms >= 0 && result.motions < lines) {
    throw new Error(`idle() resolved with ${result.motions} moves shown, not ${lines}`);
  }
  const mb = text.length / 1e6;
  console.log("| figure | value |");
  console.log("|---|---|");
  console.log(`| page load to ready (first frame) | ${ready} ms |`);
  console.log(
    `| the page's wasm: as sent (${encoding}) / gzip / uncompressed | ${wasmSizes.join(" MB / ")} MB |`,
  );
  console.log(
    `| a keystroke in a 10,000-line program to its markers drawn (median of ${KEYSTROKES}) | ${Math.round(keyMs)} ms |`,
  );
  console.log(
    `| the same keystroke in a 20-line program (median of ${KEYSTROKES}) | ${Math.round(shortKeyMs)} ms |`,
  );
  console.log(`| keystroke: 10,000 lines / 20 lines | ${(keyMs / shortKeyMs).toFixed(2)} |`);
  console.log(
    `| ${lines.toLocaleString("en")}-line program (${mb.toFixed(1)} MB) open to its full backplot drawn | ${
      result.ms < 0 ? "over 10 min" : `${Math.round(result.ms)} ms`
    } (${result.motions.toLocaleString("en")} moves) |`,
  );
  console.log(
    `| longest gap between frames: the empty page repainting / after that open() returned (the call: ${Math.round(result.call)} ms) | ${Math.round(emptyGap)} ms / ${Math.round(openGap)} ms |`,
  );
  console.log(
    `| the empty page's renderer process: resident / private | ${Math.round(emptyMb.resident)} MB / ${Math.round(emptyMb.private)} MB |`,
  );
  console.log(
    `| the page's renderer process (page and worker) with that program open: resident / private | ${Math.round(memoryMb.resident)} MB / ${Math.round(memoryMb.private)} MB |`,
  );
  console.log(
    `| of which: the page's wasm memory / the worker's / the page's JavaScript heap in use | ${partsMb.join(" MB / ")} MB |`,
  );
  console.log(
    `| the same once the page's garbage is collected: resident / private / the page's JavaScript heap | ${Math.round(collectedMb.resident)} MB / ${Math.round(collectedMb.private)} MB / ${Math.round(collectedJs / 2 ** 20)} MB |`,
  );
  console.log(
    `| the same program opened with Ctrl+O and the file picked, in a fresh page: resident / private | ${Math.round(pickedMb.resident)} MB / ${Math.round(pickedMb.private)} MB |`,
  );
  console.log(
    `| npm gcode-preview 2.18 (three.js) on the same program, to its first frame | ${Math.round(peerMs)} ms (${(peerMs / result.ms).toFixed(1)}× Swarf's time) |`,
  );
} catch (error) {
  console.error(session.withLog(`the benchmark failed: ${error.message}`));
  process.exitCode = 1;
} finally {
  await session.close();
}
