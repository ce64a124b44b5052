"""The bearer check both applications use: the header the gate reads and the one FastAPI hands
the web app's lobby (text)."""

from __future__ import annotations

import pytest

from vlln.http.gate import bearer_matches

TOKEN = "s3cret-token-0123456789"


@pytest.mark.parametrize(
    "header",
    [f"Bearer {TOKEN}", f"bearer {TOKEN}", f"Bearer  {TOKEN} ", f"Bearer {TOKEN}".encode()],
)
def test_the_token_is_accepted(header: str | bytes) -> None:
    assert bearer_matches(header, TOKEN) and bearer_matches(header, TOKEN.encode())


@pytest.mark.parametrize(
    "header", [None, "", TOKEN, f"Basic {TOKEN}", f"Bearer {TOKEN}x", "Bearer ", "Bearer é"]
)
def test_anything_else_is_refused(header: str | None) -> None:
    assert not bearer_matches(header, TOKEN)
