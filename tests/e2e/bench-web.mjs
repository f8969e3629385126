// Web benchmark (not a test): load-to-first-frame of the page, then a generated 1M-line
// surfacing program handed to the editor through `window.swarf.open`, timed until
// `window.swarf.idle()` resolves: its analysis finished in the frames, as for a person, and a
// frame showing it painted. Headless Chromium (WebGL2 through
// SwiftShader). Build first with `cargo xtask web`, then run:
//   node tests/e2e/bench-web.mjs [LINES]        (default 1000000)
// Prints a Markdown table row per figure.

import { BrowserSession } from "./harness.mjs";

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

const session = await BrowserSession.start({
  headless: true,
  args: ["--headless", "--disable-gpu", "--enable-unsafe-swiftshader"],
});
try {
  const started = Date.now();
  await session.loadUntilReady("bench-not-ready.png");
  const ready = Date.now() - started;
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
