"""The oracle: answers a navigator's questions from privileged knowledge of the house."""
