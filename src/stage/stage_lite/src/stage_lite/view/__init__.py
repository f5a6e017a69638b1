"""stageros's window and pictures: Stage 4.3's view of a world (stage_lite.model), drawn.

The pure modules (no rospy, no Tk; tested alone): camera (the window block, pan and zoom),
status (Stage's clock line and the measured real-time factor), world_picture (the one
renderer of the window and ~save_image) and world_view (what a picture draws from: trails,
bodies, robot views, the world's camera, the floor drawn per view); and gui, the Tk window
itself, which logs through rospy and is imported only when a window is wanted.
"""
