// The oracle page: the privileged map with the target, the navigator's pose, trail and view,
// and the question to answer within the time limit.
"use strict";

const page = {
  map: document.getElementById("map"),
  overlay: document.getElementById("overlay"),
  view: document.getElementById("view"),
  answer: document.getElementById("answer"),
  send: document.getElementById("send"),
  extent: null,
  mapStorey: undefined, // the storey the map shows (undefined in a house with one storey)
  mapLoading: false,
  state: null,
  shownFrame: null,
  deadline: 0,
};

function toPixel(x, z) {
  const [x0, x1, y0, y1] = page.extent;
  const width = page.overlay.width;
  const height = page.overlay.height;
  return [((x - x0) / (x1 - x0)) * width, ((y1 + z) / (y1 - y0)) * height];
}

function drawOverlay() {
  const state = page.state;
  if (!page.extent || !state || !page.map.naturalWidth) return;
  const canvas = page.overlay;
  canvas.width = page.map.naturalWidth;
  canvas.height = page.map.naturalHeight;
  const context = canvas.getContext("2d");
  context.clearRect(0, 0, canvas.width, canvas.height);
  const scale = canvas.width / 1000;
  if (state.trail.length > 1) {
    context.strokeStyle = "#1f3fbf";
    context.lineWidth = 4 * scale;
    context.beginPath();
    state.trail.forEach(([x, z], index) => {
      const [px, py] = toPixel(x, z);
      if (index === 0) context.moveTo(px, py);
      else context.lineTo(px, py);
    });
    context.stroke();
  }
  const [x, z, yaw] = state.pose;
  const [px, py] = toPixel(x, z);
  // yaw 0 looks along -z (up on the map); a positive yaw has turned left
  const dx = -Math.sin(yaw);
  const dy = -Math.cos(yaw);
  const size = 22 * scale;
  context.fillStyle = "#1f3fbf";
  context.strokeStyle = "#ffffff";
  context.lineWidth = 2 * scale;
  context.beginPath();
  context.moveTo(px + dx * size, py + dy * size);
  context.lineTo(px - dx * size * 0.6 - dy * size * 0.6, py - dy * size * 0.6 + dx * size * 0.6);
  context.lineTo(px - dx * size * 0.6 + dy * size * 0.6, py - dy * size * 0.6 - dx * size * 0.6);
  context.closePath();
  context.fill();
  context.stroke();
}

function showTarget(target) {
  const box = document.getElementById("target");
  box.replaceChildren();
  if (!target) return;
  box.append(vlln.element("div", "name", `Target: ${target.category}`));
  if (target.caption) box.append(vlln.element("div", "", target.caption));
  const facts = Object.entries(target.attributes).map(([k, v]) => `${k}: ${v}`);
  if (target.room) facts.push(`room: ${target.room}`);
  box.append(vlln.element("div", "", facts.join(" · ")));
}

function tick() {
  const timer = document.getElementById("timer");
  const left = Math.max(0, (page.deadline - performance.now()) / 1000);
  timer.textContent = `${Math.ceil(left)} s left to answer`;
}

function show(state) {
  if (page.state && state.version < page.state.version) return;
  const previous = page.state;
  page.state = state;
  document.getElementById("instruction").textContent = state.instruction;
  document.getElementById("steps").textContent = state.steps;
  document.getElementById("max-steps").textContent = state.max_steps;
  document.getElementById("questions-left").textContent = state.questions_left;
  document.getElementById("status").textContent = `Status: ${state.status}.`;
  showTarget(state.target);
  vlln.showDialog(document.getElementById("dialog"), state.dialog);
  const question = state.question;
  document.getElementById("question-area").classList.toggle("hidden", !question);
  document.getElementById("waiting").classList.toggle("hidden", !!question);
  if (question) {
    const fresh = !previous || !previous.question || previous.question.number !== question.number;
    document.getElementById("question").textContent = question.text;
    if (fresh) {
      page.answer.value = "";
      page.deadline = performance.now() + question.seconds_left * 1000;
      page.answer.focus();
    }
    tick();
  }
  if (state.frame && state.frame !== page.shownFrame) {
    page.shownFrame = state.frame;
    page.view.src = state.frame;
  }
  if (state.result) {
    const box = document.getElementById("result");
    box.textContent = vlln.resultText(state.result);
    box.className = "result " + (state.result.success ? "good" : "bad");
  }
  if (state.storey !== undefined && state.storey !== page.mapStorey && !page.mapLoading) {
    loadMap(); // the navigator took the stairs: show the storey they are on now
  }
  drawOverlay();
}

async function send() {
  const state = page.state;
  const text = page.answer.value.trim();
  if (!state || !state.question || !text) return;
  page.send.disabled = true;
  try {
    show(await vlln.withCode("POST", "/api/oracle/answer", {
      number: state.question.number,
      answer: text,
    }));
    document.getElementById("answer-error").textContent = "";
  } catch (error) {
    document.getElementById("answer-error").textContent = error.message;
  } finally {
    page.send.disabled = false;
  }
}

async function loadMap() {
  page.mapLoading = true;
  try {
    for (;;) {
      try {
        const map = await vlln.withCode("GET", "/api/oracle/map");
        page.extent = map.extent;
        page.mapStorey = map.storey;
        document.getElementById("storey").textContent = map.storey_name ? `: ${map.storey_name}` : "";
        page.map.src = map.image;
        return;
      } catch (error) {
        if (error.status === 404) return;
        await new Promise((resolve) => setTimeout(resolve, 1000));
      }
    }
  } finally {
    page.mapLoading = false;
  }
}

page.map.addEventListener("load", drawOverlay);
page.send.addEventListener("click", send);
page.answer.addEventListener("keydown", (event) => {
  if (event.key === "Enter" && !event.shiftKey) {
    event.preventDefault();
    send();
  }
});
setInterval(() => {
  if (page.state && page.state.question) tick();
}, 500);
loadMap();
vlln.follow("/api/oracle", show, (message) => {
  document.getElementById("status").textContent = `${message}. Open the link you were given.`;
});
