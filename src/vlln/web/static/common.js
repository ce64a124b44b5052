// Shared helpers of the vlln pages. Every text from the server is put in with textContent,
// never as markup, so a question or an answer shows exactly as typed.
"use strict";

const vlln = {
  code() {
    return decodeURIComponent(window.location.hash.slice(1)).trim();
  },

  async call(method, path, body, extraHeaders) {
    const headers = Object.assign({}, extraHeaders || {});
    if (body !== undefined) headers["Content-Type"] = "application/json";
    const response = await fetch(path, {
      method,
      headers,
      body: body === undefined ? undefined : JSON.stringify(body),
      cache: "no-store",
    });
    let data = null;
    try {
      data = await response.json();
    } catch (error) {
      data = null;
    }
    if (!response.ok) {
      const detail = data && data.detail ? data.detail : response.statusText;
      const failure = new Error(vlln.describeDetail(detail));
      failure.status = response.status;
      throw failure;
    }
    return data;
  },

  // An error body's detail as one line: text as it is, a list of {field, problem} (an
  // invalid request) as "field: problem; ...".
  describeDetail(detail) {
    if (typeof detail === "string") return detail;
    if (Array.isArray(detail)) {
      return detail.map((item) => (item.field ? `${item.field}: ${item.problem}` : item.problem)).join("; ");
    }
    return JSON.stringify(detail);
  },

  withCode(method, path, body) {
    return vlln.call(method, path, body, { "X-Session-Code": vlln.code() });
  },

  element(tag, className, text) {
    const node = document.createElement(tag);
    if (className) node.className = className;
    if (text !== undefined && text !== null) node.textContent = String(text);
    return node;
  },

  showDialog(list, dialog) {
    list.replaceChildren();
    dialog.forEach((turn, index) => {
      const item = vlln.element("li", turn.answered ? "turn" : "turn refused");
      item.append(vlln.element("div", "question", `Q${index + 1}: ${turn.question}`));
      item.append(vlln.element("div", "answer", turn.answer));
      list.append(item);
    });
  },

  resultText(result) {
    if (!result) return "";
    if (result.error && result.error.startsWith("abandoned")) {
      return "This episode was recorded as abandoned.";
    }
    if (result.success) return "Success: the navigator stopped at the target.";
    if (result.end_reason === "stop") return "The navigator stopped, but not at the target.";
    return `The episode ended (${result.end_reason.replace("_", " ")}).`;
  },

  // Ask the server for the role's view again and again; each answer comes as soon as
  // something changed (long polling), so pages stay current without hammering the server.
  async follow(path, show, onGone) {
    let version = 0;
    for (;;) {
      try {
        const view = await vlln.withCode("GET", `${path}?after=${version}`);
        version = view.version;
        show(view);
        if (view.result) return;
      } catch (error) {
        if (error.status === 404) {
          onGone(error.message);
          return;
        }
        await new Promise((resolve) => setTimeout(resolve, 1000));
      }
    }
  },
};
