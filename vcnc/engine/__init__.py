"""The simulation engine under `vcnc.machine`: axis definitions, the machine file, the data layout
and the compiled kernel that runs the drives."""
