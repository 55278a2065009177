// phonglab's service worker (docs/web.md, "On any web host"): a browser gives WebAssembly
// threads shared memory only on a page that is cross-origin isolated, which takes two response
// headers an ordinary static host does not send. This worker, served beside phonglab.html from
// the same folder, answers the page's own requests itself and adds them:
//   Cross-Origin-Opener-Policy: same-origin, Cross-Origin-Embedder-Policy: require-corp
// so the page (after one reload, once the worker controls it) renders on every core. It also keeps
// the last copy of the page it fetched, so the page opens offline once it has been visited.
// Nothing else is fetched or sent anywhere: a request to another origin passes through untouched.
'use strict';
const kCache = 'phonglab-v1';

self.addEventListener('install', () => self.skipWaiting());
self.addEventListener('activate', (event) => event.waitUntil(self.clients.claim()));

// The response with the isolation headers added (a copy: a response's headers are immutable).
function isolated(response) {
  if (response.status === 0) return response;  // opaque: nothing to add to
  const headers = new Headers(response.headers);
  headers.set('Cross-Origin-Opener-Policy', 'same-origin');
  headers.set('Cross-Origin-Embedder-Policy', 'require-corp');
  headers.set('Cross-Origin-Resource-Policy', 'same-origin');
  return new Response(response.body, { status: response.status, statusText: response.statusText, headers });
}

self.addEventListener('fetch', (event) => {
  const request = event.request;
  if (request.method !== 'GET' || new URL(request.url).origin !== self.location.origin) return;
  if (request.cache === 'only-if-cached' && request.mode !== 'same-origin') return;
  event.respondWith((async () => {
    const cache = await caches.open(kCache);
    // The address without its query and hash: ?scene=... and #lesson=... are the page's own.
    const key = new URL(request.url);
    key.search = '', key.hash = '';
    try {
      const response = await fetch(request);
      if (response.ok) await cache.put(key.href, response.clone());
      return isolated(response);
    } catch (error) {  // offline: the copy kept from the last visit
      const kept = await cache.match(key.href);
      if (kept) return isolated(kept);
      throw error;
    }
  })());
});
