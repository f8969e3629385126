// Browser end-to-end test of crash recovery on the web page: every tab is kept in IndexedDB, a
// record per tab, so a 30 MB program open beside a small one no longer stops the small one's
// edits from being kept; after a reload every tab comes back in order and the status bar names
// what was recovered (and says nothing of recovery when there was nothing to recover); a tab
// the browser refuses to keep is named in the status bar.
//
// Needs the web build (`cargo xtask web`); run with `node --test tests/e2e/autosave.test.mjs`.

import { after, test } from "node:test";
import assert from "node:assert/strict";

import {
  BrowserSession,
  TEST_TIMEOUT_MS,
  checkPrerequisites,
  recoveryRecords,
} from "./harness.mjs";

const CHROMIUM_ARGS = ["--headless", "--disable-gpu", "--enable-unsafe-swiftshader"];
const SMALL = "G90 G21\nG00 X0 Y0 Z5.\nG01 Z-1. F100\nM30\n";
const TYPED = "G01 X12.5 Y4. F300\n";
/** Where the editor's text area is (left column, below the tab bar), in CSS pixels. */
const EDITOR = { x: 200, y: 300 };
/**
 * Where the names of the tabs small.nc and big.nc are in the tab bar (its row is at y = 37,
 * each tab a name and a close button, pocket.nc first), in CSS pixels.
 */
const TAB = { "small.nc": { x: 165, y: 37 }, "big.nc": { x: 272, y: 37 } };
/** Bytes of the big program. */
const BIG_BYTES = 30 * 1024 * 1024;

const sessions = [];

after(async () => {
  for (const session of sessions) {
    await session.close();
  }
});

async function start() {
  checkPrerequisites();
  const session = await BrowserSession.start({ headless: true, args: CHROMIUM_ARGS });
  sessions.push(session);
  return session;
}

/**
 * Makes a G-code program of about `bytes` bytes in the page and opens it as `name`; returns its
 * length and a hash of its text, computed in the page (the text stays there).
 */
async function openBigProgram(page, name, bytes) {
  return page.evaluate(
    ([name, bytes]) => {
      const lines = [];
      let size = 0;
      for (let i = 0; size < bytes; i++) {
        const line = `N${i} G01 X${(i % 200) * 0.5} Y${(i * 7) % 300}. F1200 (finishing pass)\n`;
        lines.push(line);
        size += line.length;
      }
      const text = lines.join("");
      window.swarf.open(name, text);
      let hash = 0;
      for (let i = 0; i < text.length; i++) {
        hash = (Math.imul(hash, 31) + text.charCodeAt(i)) | 0;
      }
      return { length: text.length, hash };
    },
    [name, bytes],
  );
}

/** The active tab's text length and hash (see openBigProgram). */
function activeTextDigest(page) {
  return page.evaluate(() => {
    const text = window.swarf.getText();
    let hash = 0;
    for (let i = 0; i < text.length; i++) {
      hash = (Math.imul(hash, 31) + text.charCodeAt(i)) | 0;
    }
    return { length: text.length, hash };
  });
}

/**
 * The recovery index stored in IndexedDB and the text of the record it names for the tab
 * `name` (null when there is none); null when nothing is stored. Does not make the database.
 */
async function storedRecord(page, name) {
  const stored = await recoveryRecords(page);
  if (!stored?.index) {
    return null;
  }
  const line = stored.index
    .split("\n")
    .slice(1)
    .find((l) => l.split("\t")[3] === name);
  const key = line?.split("\t")[2];
  return { index: stored.index, text: key ? (stored.records[key] ?? null) : null };
}

/**
 * The centre of the widget `name` as the page reports it (`window.swarf.widget`, where the
 * page has it), else `fallback`.
 */
async function widgetCentre(page, name, fallback) {
  const rect = await page.evaluate((name) => {
    try {
      return window.swarf.widget?.(name) ?? null;
    } catch {
      return null;
    }
  }, name);
  return rect && rect.width > 0 && rect.height > 0
    ? { x: rect.x + rect.width / 2, y: rect.y + rect.height / 2 }
    : fallback;
}

/** Clicks the name of the tab `name` (the `position`-th) and waits until it is active. */
async function clickTab(session, name, position) {
  const { page } = session;
  const isActive = async () => {
    const tabs = await page.evaluate(() => window.swarf.tabs());
    return tabs.active === position && tabs.tabs[position]?.name === name;
  };
  // The page names tabs from 1.
  const at = await widgetCentre(page, `tab ${position + 1}`, TAB[name]);
  await page.mouse.click(at.x, at.y);
  await page.waitForTimeout(300);
  if (!(await isActive())) {
    await page.mouse.click(TAB[name].x, TAB[name].y);
  }
  await session.eventually(
    () => window.swarf.tabs(),
    null,
    (tabs) => tabs.active === position && tabs.tabs[position]?.name === name,
    `a click on the tab ${name} should make it active`,
  );
}

/**
 * Waits until the recovery index names the tab `name` and its record holds `text`; returns
 * what is stored.
 */
async function waitForRecord(session, name, text, timeoutMs = 60_000) {
  const deadline = Date.now() + timeoutMs;
  for (;;) {
    const record = await storedRecord(session.page, name);
    if (record?.text === text) {
      return record;
    }
    if (Date.now() > deadline) {
      assert.fail(
        session.withLog(
          `${name} was not kept within ${timeoutMs / 1000} s: ${JSON.stringify(record)?.slice(0, 400)}`,
        ),
      );
    }
    await session.page.waitForTimeout(250);
  }
}

/** Clicks into the editor, goes to the end of the text and types `text` key by key. */
async function typeAtEnd(page, text) {
  const at = await widgetCentre(page, "editor", EDITOR);
  await page.mouse.click(at.x, at.y);
  await page.waitForTimeout(200);
  await page.keyboard.press("Control+End");
  await page.waitForTimeout(100);
  await page.keyboard.type(text, { delay: 80 });
}

const names = (tabs) => tabs.tabs.map((t) => t.name);

test("a fresh page claims no recovery, and every tab comes back after a reload", { timeout: 2 * TEST_TIMEOUT_MS }, async () => {
  const session = await start();
  const { page } = session;
  await session.loadUntilReady("autosave-not-ready.png");
  // Nothing stored yet: nothing recovered, nothing said.
  await page.waitForTimeout(1500);
  assert.deepEqual(names(await page.evaluate(() => window.swarf.tabs())), ["pocket.nc"]);
  const fresh = await page.evaluate(() => window.swarf.status());
  assert.ok(!/recover/i.test(fresh ?? ""), `a fresh page says: ${fresh}`);

  await page.evaluate((text) => window.swarf.open("small.nc", text), SMALL);
  const big = await openBigProgram(page, "big.nc", BIG_BYTES);
  assert.ok(big.length >= BIG_BYTES, `the big program has ${big.length} bytes`);
  let tabs = await page.evaluate(() => window.swarf.tabs());
  assert.deepEqual(names(tabs), ["pocket.nc", "small.nc", "big.nc"]);
  assert.equal(tabs.active, 2);

  // A person switches to the small tab and types a line into it.
  await clickTab(session, "small.nc", 1);
  assert.equal(await page.evaluate(() => window.swarf.getText()), SMALL);
  await typeAtEnd(page, TYPED);
  const edited = await page.evaluate(() => window.swarf.getText());
  assert.equal(edited, SMALL + TYPED, "the typed line should end the small program");
  tabs = await page.evaluate(() => window.swarf.tabs());
  assert.deepEqual(
    tabs.tabs.map((t) => t.unsaved),
    [false, true, false],
    `only the small tab has unsaved changes: ${JSON.stringify(tabs)}`,
  );

  // A moment after the edit the small tab's record holds it, whatever the big one costs.
  const stored = await waitForRecord(session, "small.nc", edited);
  assert.match(stored.index, /^swarf-recovery 3\t3\t1\n/);
  assert.match(stored.index, /\ttab-[0-9a-z-]+\tbig\.nc\t/, "the big tab is kept too");
  const status = await page.evaluate(() => window.swarf.status());
  assert.ok(!/not kept/i.test(status ?? ""), `the status bar says: ${status}`);

  // Reload: every tab is back, in order, the small one active with its edit byte for byte.
  await session.loadUntilReady("autosave-reload-not-ready.png");
  tabs = await session.eventually(
    () => window.swarf.tabs(),
    null,
    (t) => t && t.tabs.length === 3,
    "the three tabs should come back after the reload",
    60_000,
  );
  assert.deepEqual(names(tabs), ["pocket.nc", "small.nc", "big.nc"]);
  assert.equal(tabs.active, 1);
  assert.deepEqual(
    tabs.tabs.map((t) => t.unsaved),
    [false, true, false],
  );
  assert.equal(await page.evaluate(() => window.swarf.getText()), edited);
  assert.equal(
    await page.evaluate(() => window.swarf.status()),
    "Recovered unsaved changes of small.nc",
  );
  // The big program is back whole.
  await clickTab(session, "big.nc", 2);
  assert.deepEqual(await activeTextDigest(page), big);
  session.assertNoPageErrors();
});

test("a tab the browser refuses to keep is named, and the others are still kept", { timeout: 2 * TEST_TIMEOUT_MS }, async () => {
  const session = await start();
  const { page } = session;
  // A browser whose quota takes no record over 1 MB.
  await page.addInitScript(() => {
    const put = IDBObjectStore.prototype.put;
    IDBObjectStore.prototype.put = function (value, key) {
      if ((value?.byteLength ?? value?.size) > 1_000_000) {
        throw new DOMException("The quota has been exceeded.", "QuotaExceededError");
      }
      return put.call(this, value, key);
    };
  });
  await session.loadUntilReady("autosave-quota-not-ready.png");
  await page.evaluate((text) => window.swarf.open("small.nc", text), SMALL);
  await openBigProgram(page, "big.nc", 4 * 1024 * 1024);
  await clickTab(session, "small.nc", 1);
  await typeAtEnd(page, TYPED);
  const edited = await page.evaluate(() => window.swarf.getText());
  assert.equal(edited, SMALL + TYPED);
  const status = await session.eventually(
    () => window.swarf.status(),
    null,
    (s) => typeof s === "string" && s.startsWith("Not kept for recovery"),
    "the status bar should say which tab is not kept",
    60_000,
  );
  assert.match(status, /^Not kept for recovery: big\.nc \(QuotaExceededError: /);
  // The small tab's edit is kept all the same.
  await waitForRecord(session, "small.nc", edited);

  await session.loadUntilReady("autosave-quota-reload-not-ready.png");
  const tabs = await session.eventually(
    () => window.swarf.tabs(),
    null,
    (t) => t && t.tabs.some((tab) => tab.name === "small.nc"),
    "the small tab should come back after the reload",
    60_000,
  );
  // The big tab had nothing unsaved and could not be kept: it is not back, and nothing claims it.
  assert.deepEqual(names(tabs), ["pocket.nc", "small.nc"]);
  assert.equal(await page.evaluate(() => window.swarf.getText()), edited);
  assert.equal(
    await page.evaluate(() => window.swarf.status()),
    "Recovered unsaved changes of small.nc",
  );
  session.assertNoPageErrors();
});
