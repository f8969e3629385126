// Browser end-to-end tests that use the page as a person does: keys typed one at a time with
// 30–150 ms between them (a seeded random delay), Enter, Tab, Escape and the arrows, and mouse
// clicks on the widgets where the page drew them (`window.swarf.widget`). After every scenario
// the program text must be exactly what was typed or chosen, nothing more, nothing less.
//
// Each scenario gets a browser of its own, so that one scenario's tabs, undo history or
// recovered program cannot change the next one's start.
//
// Environment: SWARF_WEB_DIR (default <repo>/target/web), SWARF_CHROMIUM (default
// /usr/bin/chromium), SWARF_TRUST_SEED (the typing delays' seed, default 20240611).

import { test } from "node:test";
import assert from "node:assert/strict";

import { BrowserSession, TEST_TIMEOUT_MS, checkPrerequisites, isError } from "./harness.mjs";

const CHROMIUM_ARGS = ["--headless", "--disable-gpu", "--enable-unsafe-swiftshader"];
const SEED = Number(process.env.SWARF_TRUST_SEED ?? 20240611);

/** The four-line program of the typing scenario, as typed (Enter between the lines). */
const FOUR_LINES = ["G90 G54 G00 X0 Y0", "G01 Z-1. F100", "X10. Y0.", "M30"];

/** A program with `Y0` in three places (lines 1, 3 and 5; `Y10.` is no match). */
const THREE_Y0 = "G90 G54 G00 X0 Y0\nG01 Z-1. F100\nX10. Y0.\nY10.\nX0 Y0.\nM30\n";

/** mulberry32: a small seeded generator, so a failing run's delays can be had again. */
function seeded(seed) {
  let state = seed >>> 0;
  return () => {
    state = (state + 0x6d2b79f5) >>> 0;
    let t = state;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

/** Character offsets of every occurrence of `needle` in `text`. */
function occurrences(text, needle) {
  const at = [];
  for (let i = text.indexOf(needle); i >= 0; i = text.indexOf(needle, i + 1)) {
    at.push(i);
  }
  return at;
}

/** Character offset of the start of 1-based `line` in `text`. */
function lineStart(text, line) {
  let at = 0;
  for (let n = 1; n < line; n++) {
    at = text.indexOf("\n", at) + 1;
  }
  return at;
}

/** A person at the keyboard and mouse of one page. */
class Person {
  constructor(session, seed) {
    this.session = session;
    this.page = session.page;
    this.random = seeded(seed);
  }

  /** 30–150 ms, as between two keys of a person typing. */
  async pause() {
    await sleep(30 + Math.floor(this.random() * 121));
  }

  /** Types `text` a key at a time; a line break is the Enter key. */
  async type(text) {
    for (const ch of text) {
      if (ch === "\n") {
        await this.page.keyboard.press("Enter");
      } else if (ch === "\t") {
        await this.page.keyboard.press("Tab");
      } else {
        await this.page.keyboard.type(ch);
      }
      await this.pause();
    }
  }

  /** Presses `key` (`Enter`, `Control+F`, `ArrowLeft` …) `times` times, a person's pause after each. */
  async press(key, times = 1) {
    for (let i = 0; i < times; i++) {
      await this.page.keyboard.press(key);
      await this.pause();
    }
  }

  /** Where the page drew the widget `name`, once it has drawn it. */
  async find(name) {
    return this.session.eventually(
      (n) => window.swarf.widget(n),
      name,
      (rect) => rect !== null && rect.width > 0 && rect.height > 0,
      `the page should draw the widget \`${name}\``,
    );
  }

  /** Moves the pointer to the point (`fx`, `fy`) of widget `name`'s rectangle and clicks. */
  async click(name, fx = 0.5, fy = 0.5) {
    const rect = await this.find(name);
    const x = rect.x + rect.width * fx;
    const y = rect.y + rect.height * fy;
    await this.page.mouse.move(x, y, { steps: 5 });
    await this.pause();
    await this.page.mouse.click(x, y, { delay: 40 + Math.floor(this.random() * 60) });
    await this.pause();
  }

  /**
   * Clicks the editor below its last row, near its right edge: the caret goes to the end of the
   * last line.
   */
  async clickEditorEnd() {
    await this.click("editor", 0.85, 0.8);
  }
}

/**
 * Runs one scenario in a browser of its own: `body(person, session)` acts and returns the text
 * the program must have at the end, which `getText()` must then be exactly. Fails with the
 * page's console on any page error.
 */
async function scenario(name, body, { permissions = [] } = {}) {
  checkPrerequisites();
  const session = await BrowserSession.start({ headless: true, args: CHROMIUM_ARGS });
  try {
    if (permissions.length > 0) {
      await session.context.grantPermissions(permissions, { origin: session.baseUrl });
    }
    await session.loadUntilReady(`trust-${name}-not-ready.png`);
    await session.idle();
    const seed = SEED + [...name].reduce((sum, ch) => sum + ch.charCodeAt(0), 0);
    const person = new Person(session, seed);
    let expected;
    try {
      expected = await body(person, session);
      await session.idle();
      const text = await session.page.evaluate(() => window.swarf.getText());
      assert.equal(
        text,
        expected,
        session.withLog(`${name}: the program is not exactly what was typed or chosen (seed ${seed})`),
      );
    } catch (error) {
      await session.saveFailureScreenshot(`trust-${name}.png`);
      throw error;
    }
    session.assertNoPageErrors();
  } finally {
    await session.close();
  }
}

/** The program text now. */
function textOf(session) {
  return session.page.evaluate(() => window.swarf.getText());
}

/** The editor's selection now (`{start, end, text, start_line, end_line}`). */
function selectionOf(session) {
  return session.page.evaluate(() => window.swarf.selection());
}

/** Opens `text` as the file `name` in a tab of its own (the setup of a scenario). */
async function openProgram(session, name, text) {
  await session.page.evaluate(([n, t]) => window.swarf.open(n, t), [name, text]);
  await session.idle();
  assert.equal(await textOf(session), text, `open(${name}) should show its text`);
}

/** Waits until the editor's selection satisfies `check`; returns it. */
function selectionWhen(session, check, what) {
  return session.eventually(() => window.swarf.selection(), null, check, what, 10_000);
}

test("typing a four-line program with Enter between the lines", { timeout: TEST_TIMEOUT_MS }, async () => {
  await scenario("typing", async (person, session) => {
    await openProgram(session, "typed.nc", "");
    await person.click("editor");
    await person.type(FOUR_LINES.join("\n"));
    const expected = FOUR_LINES.join("\n");
    await session.idle();
    assert.equal(await textOf(session), expected, "the typed program");
    // What the page shows is the analysis of that text.
    const problems = await session.page.evaluate(() => window.swarf.diagnostics());
    assert.ok(!problems.some(isError), `the typed program has no errors: ${JSON.stringify(problems)}`);
    const stats = await session.page.evaluate(() => window.swarf.stats());
    assert.equal(stats.blocks, 4, `stats() of the typed program: ${JSON.stringify(stats)}`);
    assert.ok(stats.motions >= 2, `stats() of the typed program: ${JSON.stringify(stats)}`);
    return expected;
  });
});

test("find: Enter in the find field steps through the matches and never edits", { timeout: TEST_TIMEOUT_MS }, async () => {
  await scenario("find", async (person, session) => {
    await openProgram(session, "find.nc", THREE_Y0);
    const matches = occurrences(THREE_Y0, "Y0");
    assert.equal(matches.length, 3);
    await person.click("editor");
    await person.press("Control+F");
    await person.find("find_field");
    await person.type("Y0");
    assert.equal(await textOf(session), THREE_Y0, "typing in the find field must not edit the program");

    let previous = null;
    for (let press = 1; press <= 3; press++) {
      await person.press("Enter");
      const selection = await selectionWhen(
        session,
        (s) => s && s.text === "Y0" && (previous === null || s.start !== previous.start),
        `Enter #${press} in the find field should select another \`Y0\` match`,
      );
      assert.ok(
        matches.includes(selection.start) && selection.end === selection.start + 2,
        `Enter #${press}: the selection ${JSON.stringify(selection)} is not a match (${matches})`,
      );
      if (previous !== null) {
        const next = matches[(matches.indexOf(previous.start) + 1) % matches.length];
        assert.equal(selection.start, next, `Enter #${press} should select the next match after ${previous.start}`);
      }
      assert.equal(await textOf(session), THREE_Y0, `Enter #${press} in the find field must not edit the program`);
      previous = selection;
    }
    // Escape closes the bar; the program is still as it was.
    await person.press("Escape");
    await session.eventually(
      () => window.swarf.widget("find_field"),
      null,
      (rect) => rect === null,
      "Escape in the find field should close the find bar",
    );
    return THREE_Y0;
  });
});

test("replace: only the Replace buttons change the text", { timeout: TEST_TIMEOUT_MS }, async () => {
  await scenario("replace", async (person, session) => {
    await openProgram(session, "replace.nc", THREE_Y0);
    await person.click("editor");
    await person.press("Control+H");
    await person.find("find_field");
    await person.type("Y0");
    await person.press("Enter");
    const match = await selectionWhen(
      session,
      (s) => s && s.text === "Y0",
      "Enter in the find field should select a `Y0` match",
    );
    assert.equal(await textOf(session), THREE_Y0, "the find field must not edit the program");

    await person.click("replace_field");
    await person.type("Y5");
    assert.equal(await textOf(session), THREE_Y0, "typing in the replace field must not edit the program");
    await person.press("Enter");
    await session.idle();
    assert.equal(await textOf(session), THREE_Y0, "Enter in the replace field must not edit the program");

    // The selected match, replaced by the Replace button.
    const selected = await selectionOf(session);
    assert.deepEqual(
      [selected.start, selected.end, selected.text],
      [match.start, match.end, "Y0"],
      "the match found should still be selected",
    );
    await person.click("replace");
    const once = THREE_Y0.slice(0, match.start) + "Y5" + THREE_Y0.slice(match.end);
    await session.eventually(
      () => window.swarf.getText(),
      null,
      (text) => text === once,
      `Replace should replace the selected match at ${match.start} and nothing else`,
      10_000,
    );
    // Replace all: every match left.
    await person.click("replace_all");
    const all = THREE_Y0.replaceAll("Y0", "Y5");
    await session.eventually(
      () => window.swarf.getText(),
      null,
      (text) => text === all,
      "Replace all should replace every match left",
      10_000,
    );
    return all;
  });
});

test("go to line: Ctrl+G, a number and Enter move the caret, never the text", { timeout: TEST_TIMEOUT_MS }, async () => {
  await scenario("goto", async (person, session) => {
    await openProgram(session, "goto.nc", THREE_Y0);
    await person.click("editor");
    // Escape leaves the dialog without going anywhere.
    const before = await selectionOf(session);
    await person.press("Control+G");
    await person.find("goto_field");
    await person.type("2");
    await person.press("Escape");
    await session.eventually(
      () => window.swarf.widget("goto_field"),
      null,
      (rect) => rect === null,
      "Escape should close the go-to-line dialog",
    );
    const after = await selectionOf(session);
    assert.deepEqual([after.start, after.end], [before.start, before.end], "Escape should not move the caret");
    assert.equal(await textOf(session), THREE_Y0, "the go-to-line dialog must not edit the program");

    await person.press("Control+G");
    await person.find("goto_field");
    await person.type("4");
    await person.press("Enter");
    const at = lineStart(THREE_Y0, 4);
    const selection = await selectionWhen(
      session,
      (s) => s && s.start_line === 4,
      "Enter in the go-to-line field should put the caret on line 4",
    );
    assert.deepEqual([selection.start, selection.end], [at, at], "the caret at the start of line 4");
    assert.equal(await textOf(session), THREE_Y0, "going to a line must not edit the program");
    await session.eventually(
      () => window.swarf.widget("goto_field"),
      null,
      (rect) => rect === null,
      "Enter should close the go-to-line dialog",
    );
    // The keyboard is back in the program: a key typed now goes in at line 4's start.
    await person.type("N4 ");
    return THREE_Y0.slice(0, at) + "N4 " + THREE_Y0.slice(at);
  });
});

test("completion: G5, 4 and Enter typed quickly give G54 and a line break", { timeout: TEST_TIMEOUT_MS }, async () => {
  await scenario("completion", async (person, session) => {
    await openProgram(session, "complete.nc", "");
    await person.click("editor");
    // Fast: the 4 and Enter within the same few milliseconds.
    await person.type("G5");
    await session.page.keyboard.press("4");
    await session.page.keyboard.press("Enter");
    await person.pause();
    await session.idle();
    assert.equal(await textOf(session), "G54\n", "G5, 4, Enter typed quickly");
    // At a person's pace, the list open since G5: Enter without a choice in it still ends the
    // line as typed.
    await person.type("G5");
    await sleep(400);
    await person.type("4");
    await sleep(400);
    await person.press("Enter");
    await session.idle();
    assert.equal(await textOf(session), "G54\nG54\n", "G5, 4, Enter typed slowly");
    // A word that is no G or M code gets no list: Tab goes into the text.
    await person.type("X1.\tY2.");
    return "G54\nG54\nX1.\tY2.";
  });
});

/** Screen positions of `points` (machine mm), once the view holds still. */
async function steadyProjection(session, points, what) {
  let previous = null;
  return session.eventually(
    (ps) => ps.map((p) => window.swarf.project(p)),
    points,
    (now) => {
      const steady =
        now.every((xy) => xy !== null) &&
        previous !== null &&
        now.every((xy, i) => Math.hypot(xy[0] - previous[i][0], xy[1] - previous[i][1]) < 0.5);
      previous = now;
      return steady;
    },
    what,
  );
}

/** Whether the view looks straight down: lines along X stay level, lines along Y upright. */
function isTopView([origin, alongX, alongY]) {
  return Math.abs(origin[1] - alongX[1]) < 0.5 && Math.abs(origin[0] - alongY[0]) < 0.5;
}

test("view keys: they go to the focused widget only", { timeout: TEST_TIMEOUT_MS }, async () => {
  await scenario("view-keys", async (person, session) => {
    // With a problem from the start, so the problems list (and with it the view's size) stays
    // as it is when the typing below adds more.
    const program = "G90 G54 G00 X0 Y0 Z5.\nG01 Z-1. F100\nX10. Y0.\nX10. Y10.\nG00 Z5.\nY$\nM30\n";
    await openProgram(session, "view.nc", program);
    const probes = [
      [0, 0, -1],
      [10, 0, -1],
      [0, 10, -1],
    ];
    const fitted = await steadyProjection(session, probes, "the view of view.nc should settle");
    assert.ok(!isTopView(fitted), `the view should not start from the top: ${JSON.stringify(fitted)}`);

    // The caret in the editor, then the pointer over an empty corner of the view, away from
    // the path and the buttons along its top.
    await person.clickEditorEnd();
    const caret = await selectionOf(session);
    assert.equal(caret.start, program.length, `the click should put the caret at the end: ${JSON.stringify(caret)}`);
    const view = await person.find("backplot");
    const corners = [
      [0.9, 0.85],
      [0.1, 0.85],
      [0.9, 0.3],
      [0.1, 0.3],
    ].map(([fx, fy]) => [view.x + view.width * fx, view.y + view.height * fy]);
    const distance = (p) => Math.min(...fitted.map((q) => Math.hypot(p[0] - q[0], p[1] - q[1])));
    const empty = corners.reduce((best, p) => (distance(p) > distance(best) ? p : best));
    await session.page.mouse.move(empty[0], empty[1], { steps: 5 });
    await person.pause();
    // The wheel zooms the view under the pointer (so a fit would show).
    await session.page.mouse.wheel(0, -240);
    await person.pause();
    const zoomed = await steadyProjection(session, probes, "the view should settle after the wheel");
    const moved = (a, b) => a.some((xy, i) => Math.hypot(xy[0] - b[i][0], xy[1] - b[i][1]) >= 0.5);
    assert.ok(moved(zoomed, fitted), `the wheel over the view should zoom it: ${JSON.stringify(fitted)} → ${JSON.stringify(zoomed)}`);

    // The editor has the keyboard: 2 and f are text, and the view stays as it is.
    await person.type("2f");
    await session.idle();
    const typed = program + "2f";
    assert.equal(await textOf(session), typed, "with the editor focused, 2 and f are typed into the program");
    const still = await steadyProjection(session, probes, "the view should hold still");
    assert.ok(
      !moved(still, zoomed),
      `keys typed into the editor must not move the view (2 is the top view, f fits): ${JSON.stringify(zoomed)} → ${JSON.stringify(still)}`,
    );

    // Escape takes the keyboard from the editor; with no widget focused, a key over the view
    // goes nowhere.
    await person.press("Escape");
    await person.press("2");
    await session.idle();
    assert.equal(await textOf(session), typed, "with nothing focused, 2 must not edit the program");
    const unfocused = await steadyProjection(session, probes, "the view should hold still");
    assert.ok(
      !moved(unfocused, zoomed),
      `with nothing focused, 2 over the view must not change it: ${JSON.stringify(zoomed)} → ${JSON.stringify(unfocused)}`,
    );

    // A click in the view gives it the keys: 2 is the top view, f fits, the text stays.
    await session.page.mouse.click(empty[0], empty[1], { delay: 50 });
    await person.pause();
    await person.press("2");
    await person.press("f");
    const top = await steadyProjection(session, probes, "the view should settle after 2 and f");
    assert.ok(isTopView(top), `2 over the focused view should show it from the top: ${JSON.stringify(top)}`);
    assert.equal(await textOf(session), typed, "keys for the view must not edit the program");
    return typed;
  });
});

test("tabs: typing in each of two tabs keeps each tab's text", { timeout: TEST_TIMEOUT_MS }, async () => {
  await scenario("tabs", async (person, session) => {
    const example = await textOf(session);
    await openProgram(session, "one.nc", "");
    // The tab strip's tabs, by their 1-based number.
    const count = async () => {
      let n = 0;
      while (await session.page.evaluate((i) => window.swarf.widget(`tab ${i}`) !== null, n + 1)) {
        n += 1;
      }
      return n;
    };
    const one = await count();
    assert.ok(one >= 2, `open() should add a tab after the example's (${one} tabs)`);

    await person.clickEditorEnd();
    await person.type("X1.\tY2.");
    // Back over "Y2." with the arrows, then in front of it.
    await person.press("ArrowLeft", 3);
    await person.type("Z0 ");
    const first = "X1.\tZ0 Y2.";
    assert.equal(await textOf(session), first, "typing in the first tab");

    await person.click("new_tab");
    await session.eventually(
      () => window.swarf.getText(),
      null,
      (text) => text === "",
      "the + button should open an empty tab",
    );
    const two = await count();
    assert.equal(two, one + 1, "the + button should add one tab");
    await person.clickEditorEnd();
    await person.type("(second)\nZ-1.");
    const second = "(second)\nZ-1.";
    assert.equal(await textOf(session), second, "typing in the second tab");

    await person.click(`tab ${one}`);
    await session.eventually(
      () => window.swarf.getText(),
      null,
      (text) => text === first,
      "the first tab should keep its text",
    );
    await person.clickEditorEnd();
    await person.type("\nX3.");
    const firstMore = `${first}\nX3.`;
    assert.equal(await textOf(session), firstMore, "typing in the first tab again");

    await person.click(`tab ${two}`);
    await session.eventually(
      () => window.swarf.getText(),
      null,
      (text) => text === second,
      "the second tab should keep its text",
    );
    await person.clickEditorEnd();
    await person.type(" F100");
    const secondMore = `${second} F100`;
    assert.equal(await textOf(session), secondMore, "typing in the second tab again");

    await person.click("tab 1");
    await session.eventually(
      () => window.swarf.getText(),
      null,
      (text) => text === example,
      "the example's tab should be untouched",
    );
    await person.click(`tab ${one}`);
    await session.eventually(
      () => window.swarf.getText(),
      null,
      (text) => text === firstMore,
      "the first tab should keep its text after the others were shown",
    );
    return firstMore;
  });
});

test("undo and redo return exactly the earlier texts", { timeout: TEST_TIMEOUT_MS }, async () => {
  await scenario("undo", async (person, session) => {
    await openProgram(session, "undo.nc", "");
    await person.click("editor");
    // Every text the program had, in order: the undo steps must be among them.
    const texts = [""];
    const typeNoting = async (s) => {
      for (const ch of s) {
        await person.type(ch);
        texts.push(texts[texts.length - 1] + ch);
      }
    };
    // A line break ends an undo step, and so does a pause of 1.5 s.
    await typeNoting("N10 X1.\nY2.");
    await sleep(2000);
    await typeNoting(" Z3.");
    const last = texts[texts.length - 1];
    assert.equal(await textOf(session), last, "the typed text");
    const mustVisit = ["N10 X1.\nY2.", "N10 X1.\n", ""];

    const undone = [];
    for (let i = 0; i < texts.length && (undone.length === 0 || undone.at(-1) !== ""); i++) {
      const before = await textOf(session);
      await person.press("Control+Z");
      const now = await session.eventually(
        () => window.swarf.getText(),
        null,
        (text) => text !== before,
        `Ctrl+Z #${i + 1} should change the text back from ${JSON.stringify(before)}`,
        10_000,
      );
      const was = texts.indexOf(before);
      const at = texts.indexOf(now);
      assert.ok(
        at >= 0 && at < was,
        `Ctrl+Z #${i + 1} gave ${JSON.stringify(now)}, which is no earlier text than ${JSON.stringify(before)}`,
      );
      undone.push(now);
    }
    assert.equal(undone.at(-1), "", `undo should come back to the empty program: ${JSON.stringify(undone)}`);
    for (const text of mustVisit) {
      assert.ok(undone.includes(text), `undo should stop at ${JSON.stringify(text)}: ${JSON.stringify(undone)}`);
    }

    // Redo walks the same steps forward, to the text as typed.
    const redone = [];
    const expected = [...undone.slice(0, -1).reverse(), last];
    for (let i = 0; i < expected.length; i++) {
      const before = await textOf(session);
      await person.press(i % 2 === 0 ? "Control+Shift+Z" : "Control+Y");
      redone.push(
        await session.eventually(
          () => window.swarf.getText(),
          null,
          (text) => text !== before,
          `redo #${i + 1} should change the text from ${JSON.stringify(before)}`,
          10_000,
        ),
      );
    }
    assert.deepEqual(redone, expected, "redo should retrace the undo steps exactly");
    return last;
  });
});

test("paste: Ctrl+V inserts exactly the clipboard's text", { timeout: TEST_TIMEOUT_MS }, async () => {
  await scenario(
    "paste",
    async (person, session) => {
      const before = "G90 G21\n";
      await openProgram(session, "paste.nc", before);
      const clip = "G00 X5. Y5.\nG01 Z-2. F200\n(pasted: ü, 銑)\nX0\n";
      await session.page.evaluate((t) => navigator.clipboard.writeText(t), clip);
      assert.equal(await session.page.evaluate(() => navigator.clipboard.readText()), clip, "the clipboard");
      await person.clickEditorEnd();
      const caret = await selectionOf(session);
      assert.equal(caret.start, before.length, `the click should put the caret at the end: ${JSON.stringify(caret)}`);
      await person.press("Control+V");
      const expected = before + clip;
      await session.eventually(
        () => window.swarf.getText(),
        null,
        (text) => text === expected,
        "Ctrl+V should insert the clipboard's text at the caret",
        10_000,
      );
      return expected;
    },
    { permissions: ["clipboard-read", "clipboard-write"] },
  );
});

test("problems: a click on the first problem selects it and edits nothing", { timeout: TEST_TIMEOUT_MS }, async () => {
  await scenario("problems", async (person, session) => {
    const broken = "G90 G21\nG01 X10 Y$ F100\nM30\n";
    await openProgram(session, "broken.nc", broken);
    const problems = await session.page.evaluate(() => window.swarf.diagnostics());
    assert.ok(problems.length > 0 && problems[0].line === 2, `the first problem is on line 2: ${JSON.stringify(problems)}`);
    await person.click("problem_first", 0.2, 0.5);
    await selectionWhen(
      session,
      (s) => s && s.start_line === 2,
      "a click on the first problem should select its place on line 2",
    );
    return broken;
  });
});
