# SPDX-License-Identifier: GPL-2.0-or-later
# Copyright (C) 2026 The GRANFRIC developers; see LICENSE and CITATION.cff.
"""A mixture of grains of two shapes (pair style keyword inertia/type): solid spheres
(q = 2/5) and hollow ones (q = 2/3) of twice the mass, elastic and perfectly rough
(r = 1, beta = 1), so that collisions conserve the kinetic energy and the gas goes to
equipartition: the translational and rotational temperatures of both species equal."""
import numpy as np

from granfric import lammpslog, lmp

INPUT = """
units           lj
atom_style      sphere
comm_modify     vel yes
region          box block 0 20 0 20 0 20
create_box      2 box
lattice         sc 0.125
create_atoms    1 box
set             type 1 type/fraction 2 0.5 4321
set             group all diameter 1.0
set             type 1 mass 1.0
set             type 2 mass 2.0
velocity        all create 1.0 4321 loop geom mom yes dist gaussian
pair_style      hardsphere/rough inertia sphere inertia/type 2 0.66666666666666663
pair_coeff      * * 1.0 1.0
fix             ed all hardsphere/ed
group           solid type 1
group           hollow type 2
compute         T1 solid hardsphere/temp
compute         T2 hollow hardsphere/temp
variable        E equal c_T1[4]+c_T1[5]+c_T2[4]+c_T2[5]
timestep        1.0
thermo          5
thermo_style    custom step time c_T1[1] c_T1[2] c_T2[1] c_T2[2] v_E f_ed[2]
thermo_modify   format float %.15g
run             400
"""


def test_two_shapes_conserve_energy_and_equipartition(tmp_path):
    script = tmp_path / "in.shapes"
    script.write_text(INPUT)
    lmp.run(str(script), cwd=str(tmp_path), log="log.shapes")
    d = lammpslog.read_thermo(str(tmp_path / "log.shapes"))
    # the energies of compute hardsphere/temp use each type's shape factor, as the collisions
    # do: with q = 2/5 for the hollow spheres the sum would not be conserved
    E = d["v_E"]
    assert np.max(np.abs(E / E[0] - 1)) < 1e-10
    assert 2.0 * d["f_ed[2]"][-1] / 1000 > 200    # collisions per particle
    # the rotational temperatures start at 0; by t = 100 (60 collisions per particle) they have
    # relaxed. The means over 100 < t <= 400 scatter by about 0.003 (T = 0.5)
    late = d["Time"] > 100
    T = {k: np.mean(d[k][late]) for k in ("c_T1[1]", "c_T1[2]", "c_T2[1]", "c_T2[2]")}
    mean = np.mean(list(T.values()))
    assert abs(mean / 0.5 - 1) < 0.02, T    # (3 translational and 3 rotational degrees)
    for t in T.values():
        assert abs(t / mean - 1) < 0.02, T
