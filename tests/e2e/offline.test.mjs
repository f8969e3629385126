// Browser end-to-end test of the page offline: after a first visit (which installs the service
// worker, web/sw.js, and caches the page, its script and the wasm app), the page reloads and
// starts with the network gone and the server stopped.
//
// Needs the web build (`cargo xtask web`); run with `node --test tests/e2e/`.

import { test } from "node:test";
import assert from "node:assert/strict";

import { TEST_TIMEOUT_MS, headlessSession } from "./harness.mjs";

const startedSession = headlessSession();

test("a reload works offline once the page was visited", { timeout: TEST_TIMEOUT_MS }, async () => {
  const session = startedSession();
  const { page, context } = session;
  await session.loadUntilReady("offline-first-visit.png");

  // The worker is installed and the page's files are in its cache.
  const cached = await session.eventually(
    async () => {
      await navigator.serviceWorker.ready;
      const names = await caches.keys();
      const files = [];
      for (const name of names) {
        const cache = await caches.open(name);
        for (const request of await cache.keys()) {
          files.push(new URL(request.url).pathname);
        }
      }
      return files;
    },
    null,
    (files) =>
      ["/swarf.js", "/swarf_app.js", "/swarf_app_bg.wasm", "/swarf.css"].every((f) =>
        files.includes(f),
      ),
    "the service worker should cache the page's script, style and wasm",
  );
  assert.ok(cached.includes("/") || cached.includes("/index.html"), `cached: ${cached}`);

  // No network: offline emulation, and the server gone as well.
  await context.setOffline(true);
  await session.stopServer();

  await page.reload({ waitUntil: "load", timeout: 60_000 });
  await page.waitForFunction(() => typeof window.swarf === "object" && window.swarf !== null, null, {
    timeout: 30_000,
  });
  const outcome = await page.evaluate(async () => {
    try {
      await window.swarf.ready;
      return { ok: true, controlled: navigator.serviceWorker.controller !== null };
    } catch (error) {
      return { ok: false, error: String(error?.stack ?? error) };
    }
  });
  assert.ok(outcome.ok, session.withLog(`offline start failed: ${outcome.error}`));
  assert.ok(outcome.controlled, "the reloaded page should be served by the service worker");
  const text = await page.evaluate(() => window.swarf.getText());
  assert.ok(text.trim().length > 0, "the editor is empty after the offline reload");
  await session.idle();
  const stats = await page.evaluate(() => window.swarf.stats());
  assert.ok(stats.motions > 0, `stats() offline: ${JSON.stringify(stats)}`);
  assert.equal(
    await page.locator("#swarf-status").isVisible(),
    false,
    "the loading message is still visible after the offline reload",
  );
});
