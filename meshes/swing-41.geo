// The swinging sheet on 41 x 41 vertices (see swing-grid.geo.inc).
N = 41;
Include "swing-grid.geo.inc";
