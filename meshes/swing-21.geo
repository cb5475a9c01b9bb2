// The swinging sheet on 21 x 21 vertices (see swing-grid.geo.inc).
N = 21;
Include "swing-grid.geo.inc";
