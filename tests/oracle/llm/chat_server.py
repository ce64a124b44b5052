"""A scripted chat-completions server on 127.0.0.1 for tests: no internet, stops by itself."""

from __future__ import annotations

import json
import threading
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from typing import Any

from vlln.oracle.llm.openai_client import MAX_REPLY_BYTES

LIFETIME_S = 30.0  # the server shuts itself down after this, whatever the test does


@dataclass(frozen=True)
class Scripted:
    """One response: status, body (a dict is sent as JSON), headers, and a delay before it.
    With ``trickle_s`` the whole response, status line first, goes out one byte at a time
    with that pause before each byte, as a stalled or hostile server might send it."""

    status: int = 200
    body: dict[str, Any] | str = ""
    headers: dict[str, str] = field(default_factory=dict)
    delay_s: float = 0.0
    trickle_s: float = 0.0


def completion(text: str, prompt_tokens: int = 7, completion_tokens: int = 3) -> Scripted:
    body = {
        "id": "chatcmpl-test",
        "object": "chat.completion",
        "choices": [{"index": 0, "message": {"role": "assistant", "content": text}}],
        "usage": {
            "prompt_tokens": prompt_tokens,
            "completion_tokens": completion_tokens,
            "total_tokens": prompt_tokens + completion_tokens,
        },
    }
    return Scripted(200, body)


def misbehaving(mode: str) -> Scripted:
    """A server failing one way of :data:`MISBEHAVING`, with delays short enough for tests
    whose clients wait well under a second."""
    return {
        "500": Scripted(500, {"error": {"message": "internal error"}}),
        "429": Scripted(429, {"error": {"message": "slow down"}}, {"Retry-After": "0"}),
        "hang": Scripted(200, completion("attribute").body, delay_s=5.0),
        "trickle": Scripted(200, completion("attribute").body, trickle_s=0.05),
        "garbage": Scripted(200, "<html>502 Bad Gateway</html>"),
        "deep": Scripted(200, "[" * 100_000),  # JSON nested past the parser's recursion limit
        "long": Scripted(200, "x" * (MAX_REPLY_BYTES + 1)),
        "empty": completion(""),  # a completion without a word
    }[mode]


MISBEHAVING = ("500", "429", "hang", "trickle", "garbage", "deep", "long", "empty")


@dataclass
class ChatServer:
    """Answers POSTs with the script in order, repeating its last entry, or with what
    ``respond`` makes of each request; records requests."""

    script: list[Scripted]
    port: int = 0
    requests: list[dict[str, Any]] = field(default_factory=list)
    respond: Callable[[dict[str, Any]], Scripted] | None = None
    _lock: threading.Lock = field(default_factory=threading.Lock)

    @property
    def base_url(self) -> str:
        return f"http://127.0.0.1:{self.port}/v1"

    def next_response(self, record: dict[str, Any]) -> Scripted:
        with self._lock:
            index = min(len(self.requests), len(self.script) - 1)
            self.requests.append(record)
            return self.respond(record) if self.respond is not None else self.script[index]


def _handler(server: ChatServer) -> type[BaseHTTPRequestHandler]:
    class Handler(BaseHTTPRequestHandler):
        def do_POST(self) -> None:
            length = int(self.headers.get("Content-Length", "0"))
            raw = self.rfile.read(length)
            record = {
                "path": self.path,
                "headers": {k.lower(): v for k, v in self.headers.items()},
                "json": json.loads(raw),
            }
            reply = server.next_response(record)
            time.sleep(reply.delay_s)
            body = reply.body if isinstance(reply.body, str) else json.dumps(reply.body)
            data = body.encode("utf-8")
            if reply.trickle_s:
                self._trickle(reply, data)
                return
            try:
                self.send_response(reply.status)
                for name, value in reply.headers.items():
                    self.send_header(name, value)
                self.send_header("Content-Length", str(len(data)))
                self.end_headers()
                self.wfile.write(data)
            except OSError:  # the client gave up (a timeout test); nothing to answer
                pass

        def _trickle(self, reply: Scripted, data: bytes) -> None:
            lines = [f"HTTP/1.1 {reply.status} OK", f"Content-Length: {len(data)}"]
            lines += [f"{name}: {value}" for name, value in reply.headers.items()]
            raw = ("\r\n".join(lines) + "\r\n\r\n").encode("latin-1") + data
            self.close_connection = True
            for index in range(len(raw)):
                time.sleep(reply.trickle_s)
                try:
                    self.wfile.write(raw[index : index + 1])
                    self.wfile.flush()
                except OSError:  # the client gave up
                    return

        def log_message(self, format: str, *args: Any) -> None:
            """Silence the per-request log lines."""

    return Handler


class _QuietServer(ThreadingHTTPServer):
    daemon_threads = True

    def handle_error(self, request: Any, client_address: Any) -> None:
        """A client that hung up mid-response is expected in timeout tests."""


@contextmanager
def chat_server(
    script: list[Scripted], respond: Callable[[dict[str, Any]], Scripted] | None = None
) -> Iterator[ChatServer]:
    """A running server for the ``with`` block, on a free loopback port."""
    server = ChatServer(script, respond=respond)
    httpd = _QuietServer(("127.0.0.1", 0), _handler(server))
    server.port = httpd.server_address[1]
    thread = threading.Thread(target=httpd.serve_forever, kwargs={"poll_interval": 0.05})
    thread.daemon = True
    thread.start()
    stopper = threading.Timer(LIFETIME_S, httpd.shutdown)
    stopper.daemon = True
    stopper.start()
    try:
        yield server
    finally:
        stopper.cancel()
        httpd.shutdown()
        httpd.server_close()
        thread.join(timeout=5.0)
