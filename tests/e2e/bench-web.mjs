// Web benchmark (not a test): load-to-first-frame of the page from a cold cache, served by
// `cargo xtask serve`, the wasm's size as sent and on disk, then a generated 1M-line
// surfacing program handed to the editor through `window.swarf.open`, timed until
// `window.swarf.idle()` resolves: its analysis finished in the page's worker, as for a person,
// and a frame showing it painted; and before it, a keystroke in a 10,000-line program, timed the
// same way. Headless Chromium (WebGL2 through
// SwiftShader). Build first with `cargo xtask web`, then run:
//   node tests/e2e/bench-web.mjs [LINES]        (default 1000000)
// Prints a Markdown table row per figure.

import { stat } from "node:fs/promises";
import path from "node:path";

import { BrowserSession, SITE } from "./harness.mjs";

const lines = Number(process.argv[2] ?? 1_000_000);

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

const session = await BrowserSession.start({
  headless: true,
  args: ["--headless", "--disable-gpu", "--enable-unsafe-swiftshader"],
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
  const keyMs = await keystroke(session, 10_000, 7);
  const text = surfacing(lines);
  const result = await session.page.evaluate(async ([name, program]) => {
    const t0 = performance.now();
    window.swarf.open(name, program);
    const late = new Promise((resolve) => setTimeout(() => resolve("late"), 600_000));
    if ((await Promise.race([window.swarf.idle(), late])) === "late") {
      return { ms: -1, motions: window.swarf.stats().motions };
    }
    return { ms: performance.now() - t0, motions: window.swarf.stats().motions };
  }, ["surfacing.nc", text]);
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
  console.log(`| a keystroke in a 10,000-line program to its markers drawn (median of 7) | ${Math.round(keyMs)} ms |`);
  console.log(
    `| ${lines.toLocaleString("en")}-line program (${mb.toFixed(1)} MB) open to its full backplot drawn | ${
      result.ms < 0 ? "over 10 min" : `${Math.round(result.ms)} ms`
    } (${result.motions.toLocaleString("en")} moves) |`,
  );
} catch (error) {
  console.error(session.withLog(`the benchmark failed: ${error.message}`));
  process.exitCode = 1;
} finally {
  await session.close();
}
