"""The I/O half of kame's action layer: action servers and clients over a program's node.

ActionServer/ServerGoalHandle and ActionClient/ClientGoalHandle speak actionlib's topics
(goal, cancel, status, feedback, result); SimpleActionServer/SimpleActionClient are the
one-goal-at-a-time forms. The rules they follow (status transitions, cancel matching,
CommState) are plain data in kame.action; `actionlib` re-exports these classes.
"""
