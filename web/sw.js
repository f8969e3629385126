// Service worker of the Swarf page: keeps the page, its script, style and the wasm app in a
// cache so that the page still starts when the network is gone.
//
// Network first: while online every request goes to the server (so a new build is picked up
// at once) and the answer replaces the cached copy; offline, the cached copy answers. The
// files of the page are cached when the worker installs, on the first visit, so a reload
// works offline even before the page asked for them a second time. Files the page fetches
// later, such as the CJK font when a Chinese interface language is chosen, are cached the
// first time they are fetched.

const CACHE = "swarf-offline-v1";

// Everything the page needs to start (paths relative to this file, the site root).
const PAGE_FILES = [
  "./",
  "./index.html",
  "./swarf.js",
  "./swarf.css",
  "./swarf_app.js",
  "./swarf_app_bg.wasm",
  "./worker.js",
  "./swarf_worker.js",
  "./swarf_worker_bg.wasm",
];

// Keeps a successful same-origin response. The body is read whole into memory first: when the
// disk is nearly full Chromium refuses large blobs, so putting the wasm's streamed body into the
// cache fails with a "network error", while the same bytes from memory are stored. The body
// read is the decoded one, so the stored copy drops the headers of the compressed transfer.
async function store(cache, request, response) {
  if (!response.ok || response.type !== "basic") {
    return;
  }
  const body = await response.arrayBuffer();
  const headers = new Headers(response.headers);
  headers.delete("Content-Encoding");
  headers.delete("Content-Length");
  await cache.put(
    request,
    new Response(body, { status: response.status, statusText: response.statusText, headers }),
  );
}

self.addEventListener("install", (event) => {
  event.waitUntil(
    (async () => {
      const cache = await caches.open(CACHE);
      // Each on its own, so that a file missing from a build does not keep the others out.
      await Promise.all(
        PAGE_FILES.map(async (file) => {
          try {
            const response = await fetch(new Request(file, { cache: "reload" }));
            await store(cache, file, response);
          } catch {
            // Not cached: that file will not be there offline.
          }
        }),
      );
      await self.skipWaiting();
    })(),
  );
});

self.addEventListener("activate", (event) => {
  event.waitUntil(
    (async () => {
      for (const name of await caches.keys()) {
        if (name.startsWith("swarf-offline-") && name !== CACHE) {
          await caches.delete(name);
        }
      }
      await self.clients.claim();
    })(),
  );
});

self.addEventListener("fetch", (event) => {
  const request = event.request;
  const url = new URL(request.url);
  if (request.method !== "GET" || url.origin !== self.location.origin) {
    return;
  }
  event.respondWith(
    (async () => {
      const cache = await caches.open(CACHE);
      try {
        const response = await fetch(request);
        // Stored beside the answer, which reaches the page as it arrives (the wasm is
        // compiled while it streams in).
        event.waitUntil(store(cache, request, response.clone()).catch(() => undefined));
        return response;
      } catch (error) {
        const cached =
          (await cache.match(request, { ignoreSearch: true })) ??
          (request.mode === "navigate" ? await cache.match("./index.html") : undefined);
        if (cached) {
          return cached;
        }
        throw error;
      }
    })(),
  );
});
