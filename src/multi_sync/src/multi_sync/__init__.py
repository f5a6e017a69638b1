"""multi_sync: the multi-robot synchronisation lesson, with turtle_lite turtles as robots."""
