// Browser end-to-end test of the interface languages: the page's first load does not fetch the
// CJK font; choosing Chinese fetches it (once) and adds it, and the choice switches live.
//
// Needs the web build (`cargo xtask web`, which puts the font in target/web/fonts/); run with
// `node --test tests/e2e/`.

import { after, before, test } from "node:test";
import assert from "node:assert/strict";

import { BrowserSession, TEST_TIMEOUT_MS, checkPrerequisites } from "./harness.mjs";

const CHROMIUM_ARGS = ["--headless", "--disable-gpu", "--enable-unsafe-swiftshader"];
const FONT = "/fonts/wqy-microhei.ttc";

let session;
const requested = [];

before(async () => {
  checkPrerequisites();
  session = await BrowserSession.start({ headless: true, args: CHROMIUM_ARGS });
  session.page.on("request", (request) => requested.push(new URL(request.url()).pathname));
});

after(async () => {
  await session?.close();
});

test("the CJK font is fetched when Chinese is chosen, not at first load", { timeout: TEST_TIMEOUT_MS }, async () => {
  const { page } = session;
  await session.loadUntilReady("language-not-ready.png");
  // Wait out the first frames: still no font.
  await page.waitForTimeout(1000);
  assert.ok(requested.includes("/swarf_app_bg.wasm"), `requests: ${requested.join(", ")}`);
  assert.ok(!requested.includes(FONT), `the first load fetched the font: ${requested.join(", ")}`);
  assert.deepEqual(await page.evaluate(() => window.swarf.language()), {
    language: "en",
    cjk_font: false,
  });

  await page.evaluate(() => window.swarf.setLanguage("zh-Hans"));
  const state = await session.eventually(
    () => window.swarf.language(),
    null,
    (s) => s && s.cjk_font === true,
    "the CJK font should be added after choosing Simplified Chinese",
    60_000,
  );
  assert.equal(state.language, "zh-Hans");
  assert.equal(requested.filter((p) => p === FONT).length, 1, `requests: ${requested.join(", ")}`);

  // Traditional Chinese uses the same font: no second fetch. English again needs none.
  await page.evaluate(() => window.swarf.setLanguage("zh-Hant"));
  await page.waitForTimeout(500);
  assert.equal((await page.evaluate(() => window.swarf.language())).language, "zh-Hant");
  await page.evaluate(() => window.swarf.setLanguage("en"));
  assert.equal(requested.filter((p) => p === FONT).length, 1, `requests: ${requested.join(", ")}`);
  const refused = await page.evaluate(() => {
    try {
      window.swarf.setLanguage("fr");
      return false;
    } catch (e) {
      return e instanceof RangeError;
    }
  });
  assert.ok(refused, "setLanguage('fr') should throw a RangeError");
  session.assertNoPageErrors();
});
