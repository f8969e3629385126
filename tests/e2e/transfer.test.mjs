// Browser end-to-end test of what the page costs to load: `cargo xtask serve` sends the wasm
// app compressed (brotli or gzip, as the request accepts), at most 2.5 MB over the network.
//
// Needs the web build (`cargo xtask web`); run with `node --test tests/e2e/transfer.test.mjs`.

import { test } from "node:test";
import assert from "node:assert/strict";
import { get } from "node:http";

import { TEST_TIMEOUT_MS, headlessSession } from "./harness.mjs";

const WASM = "swarf_app_bg.wasm";
const MAX_WASM_BYTES = 2_500_000;

const startedSession = headlessSession();

/** GET `url` with `acceptEncoding`: the status, the headers and the body's bytes as sent. */
function fetchRaw(url, acceptEncoding) {
  return new Promise((resolve, reject) => {
    const headers = acceptEncoding === undefined ? {} : { "Accept-Encoding": acceptEncoding };
    get(url, { headers }, (response) => {
      let bytes = 0;
      response.on("data", (chunk) => (bytes += chunk.length));
      response.on("end", () =>
        resolve({ status: response.statusCode, headers: response.headers, bytes }),
      );
      response.on("error", reject);
    }).on("error", reject);
  });
}

test("the page's wasm is sent compressed, at most 2.5 MB", { timeout: TEST_TIMEOUT_MS }, async () => {
  const session = startedSession();
  const { page } = session;
  const wasmResponse = page.waitForResponse((response) => response.url().endsWith(`/${WASM}`));
  await session.loadUntilReady("transfer-not-ready.png");
  const response = await wasmResponse;
  await response.finished();
  const encoding = response.headers()["content-encoding"];
  const { responseBodySize } = await response.request().sizes();
  assert.ok(["br", "gzip"].includes(encoding), `the wasm came with Content-Encoding ${encoding}`);
  assert.equal(response.headers()["content-type"], "application/wasm");
  assert.ok(
    responseBodySize > 0 && responseBodySize <= MAX_WASM_BYTES,
    `the wasm took ${responseBodySize} bytes (${encoding}) over the network, over ${MAX_WASM_BYTES}`,
  );

  // Each coding on its own (gzip for a browser without brotli is larger than the limit), and
  // the plain file for a client that accepts neither.
  const url = `${session.baseUrl}${WASM}`;
  const plain = await fetchRaw(url, undefined);
  assert.equal(plain.status, 200);
  assert.equal(plain.headers["content-encoding"], undefined);
  for (const coding of ["br", "gzip"]) {
    const sent = await fetchRaw(url, coding);
    assert.equal(sent.status, 200);
    assert.equal(sent.headers["content-encoding"], coding);
    assert.equal(sent.headers["content-type"], "application/wasm");
    assert.equal(sent.headers.vary, "Accept-Encoding");
    assert.ok(sent.bytes < plain.bytes, `${coding}: ${sent.bytes} bytes sent, ${plain.bytes} plain`);
  }
});
