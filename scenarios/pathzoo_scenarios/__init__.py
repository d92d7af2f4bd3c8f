"""Bundled scenario packs of pathzoo, registered as the ``scenarios`` plugin."""
