"""Element groups: soil Q8, layered plate strip, interface. See ``base`` for the shared array layout."""
