"""stage_multi: the Stage multi-robot lesson (robots driving straight until Stage stalls them)."""
