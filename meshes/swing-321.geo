// The swinging sheet on 321 x 321 vertices (see swing-grid.geo.inc).
N = 321;
Include "swing-grid.geo.inc";
