## -*- texinfo -*-
## @deftypefn {} {[@var{path}, @var{info}] =} shortest (@var{problem}, @var{params})
## A shortest path on the 8-connected grid with random tie-breaking (a test planner for pathzoo's Octave bridge).
##
## Distances to the goal come from repeated vectorised relaxation; the path
## then steps from the start to a neighbour on a shortest path, chosen with
## randi among the tied ones, so the seed decides which shortest path is
## returned. Among moving obstacles the vehicle waits at the start until
## driving the path at cruise speed keeps it clear of them (checked every
## 10 ms with a 0.25 m margin).
## @end deftypefn

function [path, info] = shortest (problem, params)
  blocked = problem.occupancy != 0;
  [rows, cols] = size (blocked);
  cell_size = problem.cell_size;
  start = floor (problem.start([2, 1])(:)' / cell_size) + 1;
  goal = floor (problem.goal([2, 1])(:)' / cell_size) + 1;
  moves = [-1 0; 1 0; 0 -1; 0 1; -1 -1; -1 1; 1 -1; 1 1];
  cost = [1 1 1 1 sqrt(2) sqrt(2) sqrt(2) sqrt(2)];
  [r, c] = ndgrid (1:rows, 1:cols);
  target = zeros (rows, cols, 8);
  for k = 1:8
    rr = r + moves(k, 1);
    cc = c + moves(k, 2);
    ok = ! blocked & rr >= 1 & rr <= rows & cc >= 1 & cc <= cols;
    idx = zeros (rows, cols);
    idx(ok) = sub2ind ([rows, cols], rr(ok), cc(ok));
    ok(ok) = ! blocked(idx(ok));
    if (all (moves(k, :)))
      ok(ok) &= ! blocked(sub2ind ([rows, cols], rr(ok), c(ok))) & ! blocked(sub2ind ([rows, cols], r(ok), cc(ok)));
    endif
    idx(! ok) = 0;
    target(:, :, k) = idx;
  endfor
  dist = Inf (rows, cols);
  dist(goal(1), goal(2)) = 0;
  sweeps = 0;
  do
    before = dist;
    for k = 1:8
      idx = target(:, :, k);
      ok = idx > 0;
      dist(ok) = min (dist(ok), dist(idx(ok)) + cost(k));
    endfor
    sweeps += 1;
  until (isequal (before, dist))
  info = struct ("iterations", 1, "evaluations", 1);  # one pass, whatever the sweeps
  here = sub2ind ([rows, cols], start(1), start(2));
  if (isinf (dist(here)))
    path = zeros (0, 2);
    info.status = "no_path";
    return;
  endif
  cells = here;
  while (dist(here) > 0)
    next = squeeze (target(mod (here - 1, rows) + 1, floor ((here - 1) / rows) + 1, :))';
    ok = next > 0;
    ok(ok) = abs (dist(next(ok)) + cost(ok) - dist(here)) < 1e-9;
    choices = next(ok);
    here = choices(randi (numel (choices)));
    cells(end + 1) = here;
  endwhile
  path = ([floor((cells(:) - 1) / rows), mod(cells(:) - 1, rows)] + 0.5) * cell_size;
  path(1, :) = problem.start(:)';
  path(end, :) = problem.goal(:)';
  info.history = [1, 1, dist(cells(1)) * cell_size];
  if (isfield (problem, "obstacles") && ! isempty (problem.obstacles))
    arrival = [0; cumsum(sqrt (sum (diff (path) .^ 2, 2)))] / problem.vehicle.cruise_speed;
    for wait = 0:0.5:120
      if (clear_of (problem.obstacles, path, wait + arrival))
        path = [path(1, :); path];
        info.times = [0; wait + arrival];
        return;
      endif
    endfor
    info.status = "failed";
    info.message = "no departure time within 120 s keeps clear of the moving obstacles";
  endif
endfunction

## Whether a vehicle at path(i, :) at time times(i), moving linearly in between, stays clear of every obstacle.
function ok = clear_of (obstacles, path, times)
  t = (times(1):0.01:times(end))';
  at = [interp1(times, path(:, 1), t), interp1(times, path(:, 2), t)];
  ok = true;
  for i = 1:numel (obstacles)
    ob = obstacles(i);
    if (iscell (obstacles))
      ob = obstacles{i};
    endif
    route = ob.waypoints;
    if (strcmp (ob.mode, "pingpong"))
      route = [route; route(end-1:-1:1, :)];
    else
      route = [route; route(1, :)];
    endif
    along = [0; cumsum(sqrt (sum (diff (route) .^ 2, 2)))];
    s = mod ((t + ob.phase_s) * ob.speed, along(end));
    centre = [interp1(along, route(:, 1), s), interp1(along, route(:, 2), s)];
    if (any (sqrt (sum ((at - centre) .^ 2, 2)) < ob.radius + 0.25))
      ok = false;
      return;
    endif
  endfor
endfunction
