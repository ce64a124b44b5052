// The navigator page: the first-person view, the actions and the questions. It never
// receives where anything is; it sends actions and shows the view that comes back.
"use strict";

const page = {
  view: document.getElementById("view"),
  status: document.getElementById("status"),
  question: document.getElementById("question"),
  ask: document.getElementById("ask"),
  askError: document.getElementById("ask-error"),
  stop: document.getElementById("stop"),
  leave: document.getElementById("leave"),
  shownFrame: -1,
  state: null,
  busy: false,
  stopArmed: false,
};
// Key-press-to-new-frame latencies in milliseconds, read by `vlln bench web`.
window.vllnLatencies = [];

async function showFrame(state) {
  if (state.frame_number === page.shownFrame || !state.frame) return;
  page.shownFrame = state.frame_number;
  const next = new Image();
  next.src = state.frame;
  await next.decode();
  page.view.src = next.src;
}

function canAct(state) {
  return state && state.status === "playing" && !page.busy;
}

async function show(state) {
  if (page.state && state.version < page.state.version) return; // an older reply came late
  page.state = state;
  document.getElementById("instruction").textContent = state.instruction;
  document.getElementById("steps").textContent = state.steps;
  document.getElementById("max-steps").textContent = state.max_steps;
  document.getElementById("questions-left").textContent = state.questions_left;
  document.getElementById("ask-area").classList.toggle("hidden", !state.dialog_enabled);
  document.getElementById("questions-count").classList.toggle("hidden", !state.dialog_enabled);
  vlln.showDialog(document.getElementById("dialog"), state.dialog);
  let status = state.status === "playing" ? "Your move." : `Status: ${state.status}.`;
  if (state.status === "waiting for the answer") status = "The oracle is answering your question…";
  page.status.textContent = status;
  const playing = canAct(state);
  document.querySelectorAll(".controls button").forEach((b) => (b.disabled = !playing));
  page.ask.disabled = !playing;
  page.leave.disabled = Boolean(state.result);
  page.question.disabled = !playing;
  if (state.result) {
    const box = document.getElementById("result");
    box.textContent = vlln.resultText(state.result);
    box.className = "result " + (state.result.success ? "good" : "bad");
    page.status.textContent = "The episode is over. Thank you!";
  }
  await showFrame(state);
}

async function act(action) {
  if (!canAct(page.state)) return;
  const started = performance.now();
  page.busy = true;
  try {
    const state = await vlln.withCode("POST", "/api/navigator/act", { action });
    page.busy = false;
    await show(state);
    window.vllnLatencies.push(performance.now() - started);
  } catch (error) {
    page.busy = false;
    page.status.textContent = error.message;
  }
}

async function ask() {
  const text = page.question.value.trim();
  if (!text || !canAct(page.state)) return;
  page.askError.textContent = "";
  page.busy = true;
  try {
    const state = await vlln.withCode("POST", "/api/navigator/ask", { question: text });
    page.question.value = "";
    page.busy = false;
    await show(state);
  } catch (error) {
    page.busy = false;
    page.askError.textContent = error.message;
  }
}

function armStop() {
  if (!canAct(page.state)) return;
  if (page.stopArmed) {
    page.stopArmed = false;
    page.stop.firstChild.textContent = "Stop";
    act("stop");
    return;
  }
  page.stopArmed = true;
  page.stop.firstChild.textContent = "Sure? Again";
  setTimeout(() => {
    page.stopArmed = false;
    page.stop.firstChild.textContent = "Stop";
  }, 4000);
}

async function leave() {
  if (!window.confirm("Leave this episode? It is recorded as abandoned.")) return;
  try {
    await show(await vlln.withCode("POST", "/api/navigator/end"));
  } catch (error) {
    page.status.textContent = error.message;
  }
}

const KEYS = { ArrowUp: "forward", ArrowLeft: "left", ArrowRight: "right", u: "up", d: "down" };

document.addEventListener("keydown", (event) => {
  if (event.target === page.question) {
    if (event.key === "Enter") ask();
    return;
  }
  if (event.key === "s") {
    event.preventDefault();
    armStop();
    return;
  }
  const action = KEYS[event.key];
  if (action) {
    event.preventDefault();
    act(action);
  }
});
document.querySelectorAll("[data-action]").forEach((button) => {
  button.addEventListener("click", () => act(button.dataset.action));
});
page.stop.addEventListener("click", armStop);
page.ask.addEventListener("click", ask);
page.leave.addEventListener("click", leave);

vlln.follow("/api/navigator", show, (message) => {
  page.status.textContent = `${message}. Open the link you were given, or ask the host.`;
});
