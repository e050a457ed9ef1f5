# iceDEM: dilated-polyhedron DEM for broken ice on floating structures.
# Copyright (C) 2026 iceDEM developers.  License: GPL-3.0-or-later.
#------------------------------------------------------------------------------
# Sourced by the case tests that mesh a tutorial of iceFloatingFoam whose
# hull is cut out of a block (floeApproach, mooredBox), as its Allrun does.
#
# meshHullCase [coarse]: in the current directory (a copy of the tutorial):
# 0 from 0.orig, createStructure, blockMesh, topoSet, subsetMesh (the hull
# cut out), then the cell sets and refinement levels removed. 'coarse':
# floeApproach's 48 x 24 x 6 block as 24 x 12 x 4. Logs log.<application>;
# on a failure the log's tail and return 1.
#------------------------------------------------------------------------------

meshHullCase()
{
    rm -rf 0 && cp -r 0.orig 0 || return 1
    if [ "${1:-}" = coarse ]
    then
        sed -i 's/(48 24 6)/(24 12 4)/' system/blockMeshDict
        grep -q '(24 12 4)' system/blockMeshDict \
            || { echo "blockMeshDict: no (48 24 6) to coarsen"; return 1; }
    fi
    local app
    for app in createStructure blockMesh topoSet "subsetMesh fluid -patch hull -overwrite"
    do
        $app > "log.${app%% *}" 2>&1 \
            || { echo "$app failed in $PWD:"; tail -30 "log.${app%% *}"; return 1; }
    done
    rm -rf constant/polyMesh/sets 0/cellLevel 0/pointLevel
}
