#!/usr/bin/env python3
"""A stand-in CDash for checking `ctest -D Experimental` offline.

Accepts what CTest submits (HTTP PUT or POST to submit.php), stores each file under DIR with the
query string's FileName, and answers as CDash does (<status>OK</status> with the MD5), so CTest
reports a successful submission. Usage: cdash_stub.py PORT DIR
"""
import hashlib
import http.server
import os
import sys
import urllib.parse

PORT = int(sys.argv[1])
OUT = sys.argv[2]
os.makedirs(OUT, exist_ok=True)


class Handler(http.server.BaseHTTPRequestHandler):
    def _answer(self, body: bytes) -> None:
        query = urllib.parse.parse_qs(urllib.parse.urlparse(self.path).query)
        name = os.path.basename(query.get("FileName", ["request-%d" % len(os.listdir(OUT))])[0])
        if body:
            with open(os.path.join(OUT, name), "wb") as f:
                f.write(body)
        reply = ("<cdash version=\"3.0\"><status>OK</status><message></message><md5>%s</md5></cdash>"
                 % hashlib.md5(body).hexdigest()).encode()
        self.send_response(200)
        self.send_header("Content-Type", "text/xml")
        self.send_header("Content-Length", str(len(reply)))
        self.end_headers()
        self.wfile.write(reply)

    def _body(self) -> bytes:
        length = int(self.headers.get("Content-Length", 0))
        return self.rfile.read(length) if length else b""

    def do_PUT(self):  # noqa: N802 (http.server naming)
        self._answer(self._body())

    def do_POST(self):  # noqa: N802
        self._answer(self._body())

    def log_message(self, fmt, *args):
        sys.stderr.write("cdash-stub: " + (fmt % args) + "\n")


http.server.ThreadingHTTPServer(("127.0.0.1", PORT), Handler).serve_forever()
