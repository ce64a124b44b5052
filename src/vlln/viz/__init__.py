"""Pictures of worlds and frames: top-down maps, colourised depth and instance-id images."""
