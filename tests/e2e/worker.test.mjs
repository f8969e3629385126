// Browser end-to-end test of a page whose analysis worker cannot start (its wasm does not
// load): the page analyses in its own frames instead, and draws a dense path at the zoom's
// level of detail all the same.
//
// Needs the web build (`cargo xtask web`); run with `node --test tests/e2e/`.

import { test } from "node:test";
import assert from "node:assert/strict";

import { TEST_TIMEOUT_MS, headlessSession, rasterProgram } from "./harness.mjs";

const startedSession = headlessSession();

test("without its worker the page analyses in its frames and still draws simplified", { timeout: TEST_TIMEOUT_MS }, async () => {
  const session = startedSession();
  const { page, context } = session;
  await context.route("**/swarf_worker_bg.wasm", (route) => route.abort());
  await session.loadUntilReady("worker-less-not-ready.png");
  await session.idle();
  const example = await page.evaluate(() => window.swarf.stats());
  assert.ok(example.motions > 0, `the example should be analysed in the page: ${JSON.stringify(example)}`);
  assert.equal(example.wasm_bytes.worker, 0, "no worker should have run");

  await page.evaluate(([name, text]) => window.swarf.open(name, text), ["dense.nc", rasterProgram(20_000, 200)]);
  const drawn = await session.eventually(
    () => window.swarf.stats(),
    null,
    (s) => s.motions > 20_000 && s.drawn_points !== null,
    "the opened program should be analysed and its path simplified in the page",
  );
  assert.ok(
    drawn.drawn_points > 1 && drawn.drawn_points < drawn.motions / 4,
    `the fitted view should draw the path simplified: ${JSON.stringify(drawn)}`,
  );
});
