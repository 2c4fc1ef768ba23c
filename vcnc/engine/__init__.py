"""The simulation engine: :class:`~vcnc.engine.machine.Machine` (``vcnc.machine(name)`` loads one),
axis definitions, the machine file, the data layout, FMU axes and the compiled kernel."""
