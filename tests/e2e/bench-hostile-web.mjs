// Web benchmark (not a test): the wasm memory of the page and of its analysis worker with each
// hostile program of scripts/bench-hostile.sh open, the default setup. Each program is picked in
// the page's file input after Ctrl+O, as a person opens a file, in a fresh headless Chromium
// (WebGL2 through SwiftShader); once `window.swarf.idle()` resolves the Stock button is clicked
// and the page waited for again. A wasm memory never shrinks, so its size at the end is the most
// the program made it hold: read from the `WebAssembly.Memory` of the page's module and of the
// worker's. Prints a Markdown table and exits 1 when either memory passes LIMIT_MB (1500).
// Build first with `cargo xtask web`, then run (the script generates the programs):
//   bash scripts/bench-hostile.sh --web
// which calls `node tests/e2e/bench-hostile-web.mjs DIR`, DIR holding the programs and
// `programs.tsv` (one line a program: file name, what it is, the setup file it runs with or
// nothing). TIMEOUT (900) is the seconds a program may take to be open and idle; ONLY, a regular
// expression, keeps the programs whose file name it matches.

import { readFile } from "node:fs/promises";
import path from "node:path";

import { BrowserSession, HEADLESS_ARGS, checkPrerequisites } from "./harness.mjs";

const dir = process.argv[2];
if (!dir) {
  console.error("usage: node tests/e2e/bench-hostile-web.mjs DIR (see scripts/bench-hostile.sh)");
  process.exit(2);
}
const limitMb = Number(process.env.LIMIT_MB ?? 1500);
const timeoutMs = Number(process.env.TIMEOUT ?? 900) * 1000;
const programs = (await readFile(path.join(dir, "programs.tsv"), "utf8"))
  .split("\n")
  .filter((line) => line.length > 0)
  .map((line) => line.split("\t"))
  .filter(([name]) => new RegExp(process.env.ONLY ?? "").test(name));

/** Megabytes (10^6 bytes) of the page's wasm memory, and of its worker's (null without one). */
async function wasmMb(session) {
  const page = await session.page.evaluate(async () => {
    // The module swarf.js started: a second init hands back its exports.
    const bindings = await import(new URL("swarf_app.js", document.baseURI).href);
    return (await bindings.default()).memory.buffer.byteLength;
  });
  const workers = session.page.workers();
  const worker =
    workers.length === 1
      ? await workers[0].evaluate(
          // worker.js's module, from swarf_worker.js (wasm-bindgen's no-modules output).
          async () => (await wasm_bindgen()).memory.buffer.byteLength,
        )
      : null;
  return { page: page / 1e6, worker: worker === null ? null : worker / 1e6 };
}

/** Resolves once `window.swarf.idle()` does, or rejects after TIMEOUT. */
async function idle(session, what) {
  let timer;
  const late = new Promise((_, reject) => {
    timer = setTimeout(() => reject(new Error(`${what}: not idle after ${timeoutMs / 1000} s`)), timeoutMs);
  });
  try {
    await Promise.race([session.page.evaluate(() => window.swarf.idle()), late]);
  } finally {
    clearTimeout(timer);
  }
}

/** Ctrl+O with the File System Access API hidden, and `file` picked in the file input. */
async function openFile(session, file) {
  const { page } = session;
  await page.evaluate(() => {
    window.showOpenFilePicker = undefined;
  });
  const chooser = session.nextFileChooser(60_000);
  // Keyboard shortcuts reach the app once the editor has the focus.
  await page.mouse.click(200, 300);
  await page.keyboard.press("Control+O");
  await (await chooser).setFiles(file);
  const name = path.basename(file);
  await session.eventually(
    () => window.swarf.tabs(),
    null,
    (t) => t.tabs[t.active]?.name === name,
    `${name} should open in the active tab`,
    timeoutMs,
  );
}

/** One program in a fresh browser: its figures, or the error that stopped it. */
async function measure(file, setup) {
  const session = await BrowserSession.start({ headless: true, args: HEADLESS_ARGS });
  try {
    session.interceptFileChoosers();
    await session.loadUntilReady("bench-hostile-not-ready.png");
    if (setup) {
      const toml = await readFile(path.join(dir, setup), "utf8");
      await session.page.evaluate((text) => window.swarf.setSetup(text), toml);
    }
    const t0 = Date.now();
    await openFile(session, file);
    await idle(session, "the program");
    const secs = (Date.now() - t0) / 1000;
    const opened = await wasmMb(session);
    const { motions } = await session.page.evaluate(() => window.swarf.stats());
    const codes = [
      ...new Set((await session.page.evaluate(() => window.swarf.diagnostics())).map((d) => d.code)),
    ];
    const button = await session.page.evaluate(() => window.swarf.widget("stock"));
    if (!button) {
      throw new Error("the Stock button was not drawn");
    }
    await session.page.mouse.click(button.x + button.width / 2, button.y + button.height / 2);
    await idle(session, "the stock");
    const stock = await wasmMb(session);
    const failed = session.consoleLog.some((l) => l.includes("analysis worker failed"));
    return { secs, opened, stock, motions, codes, failed };
  } catch (error) {
    return { error: session.withLog(error.message) };
  } finally {
    await session.close();
  }
}

/** `mb` rounded, in bold past the limit (or when the worker is gone). */
function cell(mb) {
  if (mb === null) {
    return "**no worker**";
  }
  const text = String(Math.round(mb));
  return mb > limitMb ? `**${text}**` : text;
}

checkPrerequisites();
console.log(
  "| program | open to idle s | page wasm MB | worker wasm MB | with the stock: page / worker MB | moves | diagnostics (codes, in order) |",
);
console.log("|---|---|---|---|---|---|---|");
let over = false;
for (const [name, what, setup] of programs) {
  const r = await measure(path.resolve(dir, name), setup);
  if (r.error) {
    over = true;
    console.log(`| ${what} | **failed** | | | | | |`);
    console.error(`${name}: ${r.error}`);
    continue;
  }
  const all = [r.opened.page, r.opened.worker, r.stock.page, r.stock.worker];
  if (r.failed || all.some((mb) => mb === null || mb > limitMb)) {
    over = true;
  }
  const codes = r.codes.slice(0, 4).join(", ") || "none";
  console.log(
    `| ${what} | ${r.secs.toFixed(1)} | ${cell(r.opened.page)} | ${cell(r.opened.worker)} | ${cell(r.stock.page)} / ${cell(r.stock.worker)} | ${r.motions.toLocaleString("en")} | ${codes}${r.failed ? " (**the worker failed**)" : ""} |`,
  );
}
if (over) {
  console.error(`bench-hostile-web: a wasm memory passed ${limitMb} MB or a program failed (in bold)`);
  process.exitCode = 1;
}
