//! `cargo xtask serve`: a small static file server for `target/web/`, which sends a file's
//! precompressed copy (`NAME.br`, `NAME.gz`, written by `cargo xtask web`) to a browser that
//! accepts it. The browser tests serve the page through it as well.

use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, Result, anyhow, bail};
use tiny_http::{Header, Method, Request, Response, Server, StatusCode};

use crate::web;

/// Number of threads answering requests (the browser loads a few files at once).
const WORKERS: usize = 4;

/// Serves `root` on `127.0.0.1:port` (port 0: a free one) until the process is interrupted.
pub fn serve(root: &Path, port: u16) -> Result<()> {
    let shown = root.display();
    if !root.join("index.html").exists() {
        bail!("{shown} has no index.html; run `cargo xtask web` first (or drop --no-build)");
    }
    let root = (root.canonicalize()).with_context(|| format!("resolving {shown}"))?;
    let address = format!("127.0.0.1:{port}");
    let server = Server::http(&address)
        .map_err(|e| anyhow!("cannot listen on {address}: {e}"))
        .map(Arc::new)?;
    // The browser tests read the address, the port chosen for port 0, from this line.
    let address = (server.server_addr().to_ip()).map_or(address, |ip| ip.to_string());
    println!("Swarf is running at http://{address}/");
    println!("(serving {}; press Ctrl-C to stop)", root.display());

    let workers: Vec<_> = (0..WORKERS)
        .map(|_| {
            let server = Arc::clone(&server);
            let root = root.clone();
            std::thread::spawn(move || {
                while let Ok(request) = server.recv() {
                    handle(&root, request);
                }
            })
        })
        .collect();
    for worker in workers {
        if worker.join().is_err() {
            bail!("a server thread stopped unexpectedly");
        }
    }
    Ok(())
}

type Answer = Response<std::io::Cursor<Vec<u8>>>;

fn handle(root: &Path, request: Request) {
    // tiny_http leaves the body out of answers to HEAD itself.
    let response = if matches!(request.method(), Method::Get | Method::Head) {
        file_response(root, &request).unwrap_or_else(|| text_response(404, "not found"))
    } else {
        text_response(405, "method not allowed")
    };
    let _ = request.respond(response);
}

/// The file `request` asks for, as its precompressed copy where the browser accepts one.
fn file_response(root: &Path, request: &Request) -> Option<Answer> {
    let path = resolve(root, request.url())?;
    let accept = (request.headers().iter()).find(|h| h.field.equiv("Accept-Encoding"));
    let accept = accept.map_or("", |h| h.value.as_str());
    let (file, encoding) = precompressed(root, &path, accept).unwrap_or((path.clone(), ""));
    let response = Response::from_data(std::fs::read(file).ok()?);
    let encoding = (!encoding.is_empty()).then_some(("Content-Encoding", encoding));
    let headers = [
        ("Content-Type", content_type(&path)),
        ("Cache-Control", "no-cache"),
        ("Vary", "Accept-Encoding"),
    ];
    let all = headers.into_iter().chain(encoding);
    Some(all.fold(response, with_header))
}

/// `response` with the header `name: value`.
fn with_header(mut response: Answer, (name, value): (&str, &str)) -> Answer {
    if let Ok(header) = Header::from_bytes(name.as_bytes(), value.as_bytes()) {
        response.add_header(header);
    }
    response
}

/// The precompressed copy of `file` to send for the request's `Accept-Encoding` header and its
/// content coding: brotli before gzip, `None` when neither is accepted or written.
fn precompressed(root: &Path, file: &Path, accept: &str) -> Option<(PathBuf, &'static str)> {
    [("br", ".br"), ("gzip", ".gz")]
        .into_iter()
        .filter(|(coding, _)| accepts(accept, coding))
        .find_map(|(coding, suffix)| Some((inside(root, &web::with_suffix(file, suffix))?, coding)))
}

/// The real path of `file` when it is a regular file under `root` (links inside the site could
/// still point elsewhere).
fn inside(root: &Path, file: &Path) -> Option<PathBuf> {
    let real = file.canonicalize().ok()?;
    (real.starts_with(root) && real.is_file()).then_some(real)
}

/// Whether an `Accept-Encoding` value allows `coding`: named, or else `*`, with a q above 0.
fn accepts(accept: &str, coding: &str) -> bool {
    let quality = |name: &str| {
        accept.split(',').find_map(|item| {
            let mut parts = item.split(';');
            let listed = parts.next()?.trim().eq_ignore_ascii_case(name);
            listed.then(|| {
                parts
                    .find_map(|p| p.trim().strip_prefix("q=")?.trim().parse::<f32>().ok())
                    .unwrap_or(1.0)
            })
        })
    };
    (quality(coding).or_else(|| quality("*"))).is_some_and(|q| q > 0.0)
}

fn text_response(status: u16, text: &str) -> Answer {
    let response = Response::from_string(text).with_status_code(StatusCode(status));
    with_header(response, ("Content-Type", "text/plain; charset=utf-8"))
}

/// Maps a request URL to a regular file under `root` (a folder to its `index.html`), or `None`
/// (404) for anything outside it, with a `..` component, NUL, a backslash or a malformed escape.
fn resolve(root: &Path, url: &str) -> Option<PathBuf> {
    let path = url.split(['?', '#']).next().unwrap_or_default();
    let hex = |e: &str| {
        e.get(..2)
            .is_some_and(|h| h.bytes().all(|b| b.is_ascii_hexdigit()))
    };
    if !path.split('%').skip(1).all(hex) {
        return None;
    }
    let decoded = percent_encoding::percent_decode_str(path)
        .decode_utf8()
        .ok()?;
    if decoded.contains(['\0', '\\']) {
        return None;
    }
    let mut file = root.to_path_buf();
    for component in Path::new(&*decoded).components() {
        match component {
            Component::Normal(part) => file.push(part),
            Component::RootDir | Component::CurDir => {}
            Component::ParentDir | Component::Prefix(_) => return None,
        }
    }
    if file.is_dir() {
        file.push("index.html");
    }
    inside(root, &file)
}

/// The MIME type for a file, from its extension.
fn content_type(path: &Path) -> &'static str {
    let extension = (path.extension().and_then(|e| e.to_str())).map(str::to_ascii_lowercase);
    match extension.as_deref() {
        Some("html" | "htm") => "text/html; charset=utf-8",
        Some("js" | "mjs") => "text/javascript; charset=utf-8",
        Some("css") => "text/css; charset=utf-8",
        Some("wasm") => "application/wasm",
        Some("png") => "image/png",
        Some("jpg" | "jpeg") => "image/jpeg",
        Some("svg") => "image/svg+xml",
        Some("ico") => "image/x-icon",
        Some("json" | "map") => "application/json",
        Some("txt" | "nc" | "ngc" | "gcode" | "tap" | "cnc" | "md") => "text/plain; charset=utf-8",
        _ => "application/octet-stream",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A small site in a temporary folder of its own for the test `name`.
    fn site(name: &str) -> std::io::Result<PathBuf> {
        let dir =
            std::env::temp_dir().join(format!("xtask-serve-test-{}-{name}", std::process::id()));
        std::fs::create_dir_all(dir.join("assets"))?;
        std::fs::write(dir.join("index.html"), "<html></html>")?;
        std::fs::write(dir.join("swarf_app_bg.wasm"), [0u8, 97, 115, 109])?;
        std::fs::write(dir.join("assets").join("a b.nc"), "G0 X0")?;
        dir.canonicalize()
    }

    #[test]
    fn resolves_files_and_rejects_traversal() -> std::io::Result<()> {
        let root = site("resolve")?;
        assert_eq!(resolve(&root, "/"), Some(root.join("index.html")));
        assert_eq!(
            resolve(&root, "/index.html?v=1"),
            Some(root.join("index.html"))
        );
        assert_eq!(
            resolve(&root, "/assets/a%20b.nc"),
            Some(root.join("assets").join("a b.nc"))
        );
        assert_eq!(resolve(&root, "/missing.js"), None);
        assert_eq!(resolve(&root, "/../Cargo.toml"), None);
        assert_eq!(resolve(&root, "/assets/../../etc/passwd"), None);
        assert_eq!(resolve(&root, "/%2e%2e/%2e%2e/etc/passwd"), None);
        assert_eq!(resolve(&root, "/%2E%2E%2Fetc%2Fpasswd"), None);
        assert_eq!(resolve(&root, "/..%5c..%5cetc"), None);
        // A malformed escape is refused, even where a file has that name.
        std::fs::write(root.join("bad%zz"), "x")?;
        assert_eq!(resolve(&root, "/bad%zz"), None);
        assert_eq!(resolve(&root, "/bad%2"), None);
        std::fs::remove_dir_all(&root)
    }

    #[test]
    fn accept_encoding() {
        assert!(accepts("gzip, deflate, br, zstd", "br"));
        assert!(accepts("gzip, deflate, br, zstd", "gzip"));
        assert!(!accepts("gzip, deflate", "br"));
        assert!(!accepts("br;q=0, gzip", "br"));
        assert!(accepts("br;q=0.5", "br"));
        assert!(accepts("*", "br"));
        assert!(!accepts("br;q=0, *", "br"));
        assert!(!accepts("", "gzip"));
        assert!(!accepts("identity", "gzip"));
    }

    #[test]
    fn precompressed_copies_when_accepted() -> std::io::Result<()> {
        let root = site("compressed")?;
        let wasm = root.join("a.wasm");
        for name in ["a.wasm", "a.wasm.br", "a.wasm.gz", "b.js", "b.js.gz"] {
            std::fs::write(root.join(name), name)?;
        }
        assert_eq!(
            precompressed(&root, &wasm, "gzip, br"),
            Some((root.join("a.wasm.br"), "br"))
        );
        assert_eq!(
            precompressed(&root, &wasm, "gzip"),
            Some((root.join("a.wasm.gz"), "gzip"))
        );
        assert_eq!(precompressed(&root, &wasm, "identity"), None);
        assert_eq!(
            precompressed(&root, &root.join("b.js"), "br, gzip"),
            Some((root.join("b.js.gz"), "gzip"))
        );
        std::fs::remove_dir_all(&root)
    }

    #[test]
    fn mime_types() {
        assert_eq!(
            content_type(Path::new("swarf_app_bg.wasm")),
            "application/wasm"
        );
        assert!(content_type(Path::new("swarf.js")).starts_with("text/javascript"));
        assert!(content_type(Path::new("index.html")).starts_with("text/html"));
        assert!(content_type(Path::new("swarf.css")).starts_with("text/css"));
        assert_eq!(content_type(Path::new("shot.PNG")), "image/png");
    }
}
