// The lobby: start a session (the host of a study) or join one with a code (participants).
"use strict";

const lobby = { token: sessionStorage.getItem("vlln-token") || "" };

function auth() {
  return lobby.token ? { Authorization: `Bearer ${lobby.token}` } : {};
}

function option(select, value, text) {
  const item = document.createElement("option");
  item.value = value;
  item.textContent = text;
  select.append(item);
}

async function load() {
  let info;
  try {
    info = await vlln.call("GET", "/api/lobby", undefined, auth());
  } catch (error) {
    if (error.status === 401) document.getElementById("token-area").classList.remove("hidden");
    document.getElementById("create-error").textContent = error.message;
    return;
  }
  document.getElementById("token-area").classList.add("hidden");
  document.getElementById("create-error").textContent = "";
  const navigator = document.getElementById("navigator");
  navigator.replaceChildren();
  option(navigator, "human", "a person (this browser or another)");
  info.agents.forEach((name) => option(navigator, name, `agent: ${name}`));
  const oracle = document.getElementById("oracle");
  oracle.replaceChildren();
  const names = {
    rules: "rule-based oracle",
    helpful: "helpful oracle (beyond the paper)",
    llm: "language-model oracle",
    human: "a person",
  };
  info.oracles.forEach((kind) => option(oracle, kind, names[kind] || kind));
  const episode = document.getElementById("episode");
  episode.replaceChildren();
  option(episode, "", "next one not yet played");
  info.episodes.forEach((e) => option(episode, e.index, `${e.index}: ${e.instruction} (${e.scene_id})`));
  const s = info.sessions;
  document.getElementById("overview").textContent =
    `Task ${info.task.toUpperCase()}, ${info.budget} answered questions per episode, ` +
    `${info.episodes.length} episodes. Sessions: ${s.live} live, ${s.finished} finished, ` +
    `${s.abandoned} abandoned. Episode records written: ${s.records}.`;
}

function showCode(role, code, page) {
  document.getElementById(`${role}-line`).classList.toggle("hidden", !code);
  if (!code) return;
  document.getElementById(`${role}-code`).textContent = code;
  document.getElementById(`${role}-link`).href = `${page}#${encodeURIComponent(code)}`;
}

async function create() {
  const episode = document.getElementById("episode").value;
  const body = {
    navigator: document.getElementById("navigator").value,
    participant: document.getElementById("participant").value.trim() || null,
    oracle: document.getElementById("oracle").value,
    episode_index: episode === "" ? null : Number(episode),
  };
  try {
    const created = await vlln.call("POST", "/api/sessions", body, auth());
    document.getElementById("create-error").textContent = "";
    document.getElementById("created").classList.remove("hidden");
    showCode("navigator", created.navigator_code, "/navigate");
    showCode("oracle", created.oracle_code, "/answer");
    load();
  } catch (error) {
    document.getElementById("create-error").textContent = error.message;
  }
}

async function join() {
  const code = document.getElementById("join-code").value.trim();
  if (!code) return;
  try {
    const found = await vlln.call("POST", "/api/join", { code });
    window.location.assign(`${found.page}#${encodeURIComponent(code)}`);
  } catch (error) {
    document.getElementById("join-error").textContent = error.message;
  }
}

document.getElementById("create").addEventListener("click", create);
document.getElementById("join").addEventListener("click", join);
document.getElementById("use-token").addEventListener("click", () => {
  lobby.token = document.getElementById("token").value.trim();
  sessionStorage.setItem("vlln-token", lobby.token);
  load();
});
load();
