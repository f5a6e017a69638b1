"""Stage 4.3.0's own controllers, ported rule for rule to Stage's plugin interface in Python
(stage_lite.model.stage_api); a world names them with `ctrl "name args"` (no rospy).

Each module has init(model, args), as Stage's plugins have Init(Model*, CtrlArgs*).
"""
