"""The convoy practice: followers chasing their leader turtle, plus an autopilot leader."""
