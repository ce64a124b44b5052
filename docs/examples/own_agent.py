"""An agent of one's own: walks on while the depth image shows nothing close ahead and its
last step moved it, else turns at random; asks the oracle once; stops after 80 steps.
From this folder: vlln eval --agent own_agent:DepthWalker --task iign --out runs/mine"""

import numpy as np

from vlln.sim.agent import Action
from vlln.tasks.env import EpisodeInfo, Observation
from vlln.tasks.spec import AgentOutput, Talk


class DepthWalker:
    name = "depth-walker"
    privileged = False  # True adds instance ids and the expert's next action to observations

    def __init__(self, seed: int) -> None:  # a fresh agent per episode and budget, seeded
        self.rng = np.random.default_rng(seed)

    def reset(self, episode: EpisodeInfo) -> None:
        self.steps, self.asked, self.target = 0, False, episode.object_category
        self.last_gps: np.ndarray | None = None  # where the last MOVE_FORWARD started

    def act(self, observation: Observation) -> AgentOutput:
        self.steps += 1
        if not self.asked and observation["questions_left"] > 0:
            self.asked = True  # the answer comes in the next observation's "oracle_answer"
            return Talk(f"Which way is the {self.target}?")
        if self.steps > 80:
            return Action.STOP
        gps = observation["gps"]  # (x, z) in metres from the start
        moved = self.last_gps is None or np.hypot(*(gps - self.last_gps)) > 0.1
        depth = observation["depth"]  # z-depth in metres; 0 where nothing was drawn (far)
        rows, cols = depth.shape
        ahead = depth[rows // 2 :, cols // 3 : 2 * cols // 3]  # below the horizon, centre
        self.last_gps = None
        if moved and np.where(ahead > 0, ahead, 10.0).min() > 0.75:
            self.last_gps = gps.copy()
            return Action.MOVE_FORWARD
        return Action.TURN_LEFT if self.rng.random() < 0.5 else Action.TURN_RIGHT
