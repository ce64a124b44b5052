"""People in the loop: a web app where humans navigate, answer an agent's questions, or both.

``vlln serve web`` serves a lobby (create a session, join one with a code), a navigator page
(first-person view, actions, questions) and an oracle page (the privileged map, the
navigator's view, the question and a time limit). Every episode played is an ordinary episode
record in the output folder, scored by ``vlln score`` like any other.
"""
