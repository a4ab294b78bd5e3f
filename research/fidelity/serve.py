"""A loopback HTTP server for the render pages, the npm packages and the models.

Pages cannot import ES modules or fetch glTF buffers from file: URLs, so the
browser is given http://127.0.0.1:PORT/ with a few folders mounted under fixed
prefixes. Read-only, loopback only, on a free port, in a thread of its own.
"""

import http.server
import io
import os
import posixpath
import threading
import urllib.parse

# Module scripts are refused unless served as JavaScript, and WebAssembly is
# compiled while streaming only when served as application/wasm; the platform's
# mime.types need not know either.
TYPES = {
    ".html": "text/html", ".js": "text/javascript", ".mjs": "text/javascript",
    ".wasm": "application/wasm", ".json": "application/json",
    ".gltf": "model/gltf+json", ".glb": "model/gltf-binary",
    ".bin": "application/octet-stream", ".png": "image/png", ".jpg": "image/jpeg",
    ".jpeg": "image/jpeg", ".ktx2": "image/ktx2", ".webp": "image/webp",
}


class Server:
    """Serves mounts ({"/prefix/": "/some/folder"}) on 127.0.0.1, and files given
    as bytes ({"/path.js": b"..."}), which win over the mounts; use as a context
    manager."""

    def __init__(self, mounts, files=None):
        self.mounts = {prefix: os.path.realpath(folder) for prefix, folder in mounts.items()}
        self.files = dict(files or {})
        server = self

        class Handler(http.server.SimpleHTTPRequestHandler):
            extensions_map = TYPES

            def send_head(self):
                body = server.files.get(urllib.parse.urlsplit(self.path).path)
                if body is None:
                    return super().send_head()
                self.send_response(200)
                self.send_header("Content-Type", self.guess_type(self.path))
                self.send_header("Content-Length", str(len(body)))
                self.end_headers()
                return io.BytesIO(body)

            def translate_path(self, path):
                return server.resolve(path)

            def list_directory(self, path):  # no listings: only files are asked for
                self.send_error(404)
                return None

            def log_message(self, *args):  # the caller reports progress
                pass

        self.httpd = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Handler)
        self.base = "http://127.0.0.1:%d" % self.httpd.server_address[1]
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)

    def resolve(self, url_path):
        """The file a URL path names, or a path that does not exist (a 404)."""
        path = posixpath.normpath(urllib.parse.unquote(url_path.split("?", 1)[0]))
        for prefix, folder in self.mounts.items():
            if (path + "/").startswith(prefix):
                full = os.path.realpath(os.path.join(folder, path[len(prefix):]))
                if full == folder or full.startswith(folder + os.sep):
                    return full
        return "/nonexistent"

    def url(self, prefix, relative=""):
        return self.base + prefix + urllib.parse.quote(relative)

    def __enter__(self):
        self.thread.start()
        return self

    def __exit__(self, *exc):
        self.httpd.shutdown()
        self.httpd.server_close()
