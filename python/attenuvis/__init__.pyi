from . import mie as mie, visgraph as visgraph, weather as weather

__version__: str
