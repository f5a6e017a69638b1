"""rviz around the lessons: what a .rviz file subscribes to (config), is rviz's view showing
the lesson yet (screen, with the markers' colours), and rviz on a private Xvfb (snapshot)."""
