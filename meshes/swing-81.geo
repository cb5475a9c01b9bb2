// The swinging sheet on 81 x 81 vertices (see swing-grid.geo.inc).
N = 81;
Include "swing-grid.geo.inc";
