// Browser end-to-end test of the machine setup through `window.swarf`: a SETUP.toml with a stock
// and a tool applied with setSetup() comes back from setup(), and a setup the CLI would refuse
// throws and changes nothing.
//
// Needs the web build (`cargo xtask web`); run with `node --test tests/e2e/`.

import { test } from "node:test";
import assert from "node:assert/strict";

import { TEST_TIMEOUT_MS, headlessSession } from "./harness.mjs";

const SETUP = `[stock]
min = [0.0, 0.0, -20.0]
max = [100.0, 50.0, 0.0]

[tools.1]
diameter = 6.0
shape = "ball"
flute_length = 12.0
`;

const startedSession = headlessSession();

test("setSetup applies a SETUP.toml that setup() gives back; a bad one throws", { timeout: TEST_TIMEOUT_MS }, async () => {
  const session = startedSession();
  const { page } = session;
  await session.loadUntilReady("setup-not-ready.png");
  const before = await page.evaluate(() => window.swarf.setup());
  assert.ok(!before.includes("[stock]"), before);

  await page.evaluate((toml) => window.swarf.setSetup(toml), SETUP);
  const text = await page.evaluate(() => window.swarf.setup());
  const lines = text.split("\n");
  for (const line of [
    "[stock]",
    "min = [0.0, 0.0, -20.0]",
    "max = [100.0, 50.0, 0.0]",
    "[tools.1]",
    "diameter = 6.0",
    'shape = "ball"',
    "flute_length = 12.0",
  ]) {
    assert.ok(lines.includes(line), `setup() lacks ${line}:\n${text}`);
  }
  // The setup round-trips: applying its own text changes nothing.
  await page.evaluate((toml) => window.swarf.setSetup(toml), text);
  assert.equal(await page.evaluate(() => window.swarf.setup()), text);

  for (const bad of [
    "[stock]\nmin = [0, 0, 0]\nmax = [-10, 10, 10]\n",
    '[tools.2]\ndiameter = 4.0\nshape = "bull"\n',
    "[machine]\nrapid_mm_per_min = 0\n",
    "nonsense = [",
  ]) {
    const thrown = await page.evaluate((toml) => {
      try {
        window.swarf.setSetup(toml);
        return null;
      } catch (e) {
        return { isError: e instanceof Error, message: String(e.message) };
      }
    }, bad);
    assert.ok(thrown?.isError, `setSetup(${JSON.stringify(bad)}) should throw an Error`);
    assert.match(thrown.message, /^SETUP\.toml: /, thrown.message);
    assert.equal(await page.evaluate(() => window.swarf.setup()), text, "a refused setup changed it");
  }
  session.assertNoPageErrors();
});
