"""What the HTTP applications (the oracle service and the web app) share: loopback checks,
the request gate (bearer token, body size, JSON content type), JSON error bodies and the
uvicorn server they run in. :mod:`.addresses` needs only the standard library, so clients
below the applications (the OpenAI-compatible client) use it without the ``serve`` extra."""
