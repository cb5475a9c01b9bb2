// The swinging sheet on 161 x 161 vertices (see swing-grid.geo.inc).
N = 161;
Include "swing-grid.geo.inc";
