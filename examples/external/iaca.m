## -*- texinfo -*-
## @deftypefn {} {[@var{path}, @var{info}] =} iaca (@var{problem}, @var{params})
## Improved ant colony algorithm for off-road paths (Wang et al. 2018), as an Octave/MATLAB function.
##
## Written for pathzoo's planner protocol (docs/external-planners.md), from
## the paper (section 3, eqs. 13-21, parameters of section 4.1); equation
## numbers below are the paper's. Runs unchanged in MATLAB: call it with a
## problem struct of the same fields.
##
## The pheromone lives on grid cells. A move is GO when its slope lies in
## [-descent_deg, climb_deg] (the slope tabu table, section 2.1) and the
## target cell's rating cone index exceeds the vehicle's (the soil tabu
## table, section 2.2). Each ant walks from the start, choosing among the GO
## neighbours it has not visited by roulette on ph^alpha * H^beta (eq. 13,
## H of eq. 14), lowering the pheromone of each cell it enters (eq. 15); an
## ant with no choice left is dropped (eq. 20). After each colony the cells
## of the iteration's shortest path move toward K / its distance (eqs.
## 16-17). Pheromone stays within [ph_min, ph_max] (eq. 18). Distance is
## eq. 21: the sum over steps of the 3-D step length in cells over slopeW.
##
## @var{params} may set n_ants, iterations, alpha, beta, j, decr, rho, k,
## ph0, ph_min, ph_max, climb_deg and descent_deg (defaults: section 4.1).
## The budget's iterations and evaluations (ant walks) limits and its time
## limit (a stop only) are respected; without any limit the colony runs
## params.iterations (NCmax).
## @end deftypefn

function [path, info] = iaca (problem, params)
  p = struct ("n_ants", 40, "iterations", 100, "alpha", 3, "beta", 4, "j", 200, "decr", 0.1, ...
              "rho", 0.4, "k", 500, "ph0", 0.4, "ph_min", 0.001, "ph_max", 0.8, ...
              "climb_deg", 30, "descent_deg", 60);
  for name = fieldnames (params)'
    p.(name{1}) = params.(name{1});
  endfor
  budget = problem.budget;
  n_iterations = Inf;  # like pathzoo's colonies: the paper's count only when the budget sets no limit
  if (! isempty (budget.iterations))
    n_iterations = budget.iterations;
  elseif (isempty (budget.evaluations) && isempty (budget.time_s))
    n_iterations = p.iterations;
  endif
  max_walks = Inf;
  if (! isempty (budget.evaluations))
    max_walks = budget.evaluations;
  endif
  started = tic ();

  [next, heuristic, distance] = move_tables (problem, p);
  [rows, cols] = size (problem.occupancy);
  cell_size = problem.cell_size;
  origin = cell_index (problem.start, cell_size, rows);
  target = cell_index (problem.goal, cell_size, rows);
  max_steps = 2 * nnz (any (next > 0, 2)) + 2;
  ph = repmat (p.ph0, rows * cols, 1);
  weight = heuristic .^ p.beta;

  best_cost = Inf;
  best_cells = [];
  history = zeros (0, 3);
  walks = 0;
  iteration = 0;
  while (iteration < n_iterations && walks < max_walks)
    if (! isempty (budget.time_s) && toc (started) >= budget.time_s)
      break;
    endif
    iteration += 1;
    n_ants = min (p.n_ants, max_walks - walks);
    it_cost = Inf;
    it_cells = [];
    for ant = 1:n_ants
      walks += 1;
      [cells, cost, ph] = walk (origin, target, next, weight, distance, ph, p, max_steps);
      if (cost < it_cost)
        it_cost = cost;
        it_cells = cells;
      endif
    endfor
    if (isfinite (it_cost))
      ## eqs. 16-17: the iteration's shortest path pulls its cells toward K / Dist_min; eq. 18 clamps
      entered = it_cells(2:end);
      ph(entered) = min (p.ph_max, max (p.ph_min, (1 - p.rho) * ph(entered) + p.rho * p.k / it_cost));
      if (it_cost < best_cost)
        best_cost = it_cost;
        best_cells = it_cells;
      endif
    endif
    history(end + 1, :) = [iteration, walks, best_cost];
  endwhile

  info = struct ("iterations", iteration, "evaluations", walks, "history", history);
  if (isempty (best_cells))
    path = zeros (0, 2);
    info.status = "failed";
    info.message = "no ant reached the goal";
    return;
  endif
  path = centre_path (best_cells, rows, cell_size, problem.start(:)', problem.goal(:)');
  info.status = "solved";
  info.message = sprintf ("eq. 21 distance %.4f", best_cost);
endfunction

## The cells of one ant's walk (linear indices, start first) and its eq. 21 distance (Inf if dropped).
function [cells, cost, ph] = walk (origin, target, next, weight, distance, ph, p, max_steps)
  visited = false (size (ph));
  visited(origin) = true;
  cells = zeros (1, max_steps + 1);
  cells(1) = origin;
  n = 1;
  cost = 0;
  here = origin;
  while (here != target)
    to = next(here, :);
    open = to > 0;
    open(open) = ! visited(to(open));
    w = zeros (1, 8);
    w(open) = ph(to(open))' .^ p.alpha .* weight(here, open);  # eq. 13: ph^alpha H^beta, 0 where H = 0
    total = sum (w);
    if (total <= 0 || n > max_steps)
      cost = Inf;  # eq. 20: a walk that does not end at the target does not count
      return;
    endif
    move = find (cumsum (w) >= rand () * total, 1);  # roulette
    here = to(move);
    cost += distance(cells(n), move);
    ph(here) = min (p.ph_max, max (p.ph_min, (1 - p.decr) * ph(here)));  # eq. 15, clamped by eq. 18
    visited(here) = true;
    n += 1;
    cells(n) = here;
  endwhile
  cells = cells(1:n);
endfunction

## Per cell (linear index) and move (8 neighbours): the target cell (0 for none), eq. 14's H and eq. 21's step.
function [next, heuristic, distance] = move_tables (problem, p)
  blocked = problem.occupancy != 0;
  [rows, cols] = size (blocked);
  z = zeros (rows, cols);
  if (isfield (problem, "elevation") && ! isempty (problem.elevation))
    z = problem.elevation;
    blocked |= isnan (z);
  endif
  slope_table = [];
  soil_go = true (rows, cols);
  if (isfield (problem, "rules"))
    slope_table = problem.rules.slope_weights;
    if (! isempty (problem.rules.soil_strength) && ! isempty (problem.rules.min_soil_strength))
      soil_go = problem.rules.soil_strength > problem.rules.min_soil_strength;  # soil tabu table, strict
    endif
  endif
  cell_size = problem.cell_size;
  goal = cell_index (problem.goal, cell_size, rows);
  [goal_r, goal_c] = ind2sub ([rows, cols], goal);
  [r, c] = ndgrid (1:rows, 1:cols);
  ## Q: 3-D Euclidean distance from each cell centre to the target's, in cells
  to_goal = sqrt ((r - goal_r) .^ 2 + (c - goal_c) .^ 2 + ((z - z(goal)) / cell_size) .^ 2);
  dr = [-1, 1, 0, 0, -1, -1, 1, 1];
  dc = [0, 0, -1, 1, -1, 1, -1, 1];
  n = rows * cols;
  next = zeros (n, 8);
  heuristic = zeros (n, 8);
  distance = Inf (n, 8);
  for move = 1:8
    rr = r + dr(move);
    cc = c + dc(move);
    inside = rr >= 1 & rr <= rows & cc >= 1 & cc <= cols & ! blocked;
    to = zeros (rows, cols);
    to(inside) = sub2ind ([rows, cols], rr(inside), cc(inside));
    ok = inside;
    ok(inside) = ! blocked(to(inside));
    if (dr(move) != 0 && dc(move) != 0)  # a diagonal move touches both orthogonal neighbours' cells
      side_r = sub2ind ([rows, cols], min (max (rr, 1), rows), c);
      side_c = sub2ind ([rows, cols], r, min (max (cc, 1), cols));
      ok &= ! blocked(side_r) & ! blocked(side_c);
    endif
    run = hypot (dr(move), dc(move));  # the move's horizontal length, in cells
    dz = zeros (rows, cols);
    dz(ok) = (z(to(ok)) - z(ok)) / cell_size;
    slope = atand (dz / run);  # eqs. 3-10: tangent of the slope to the neighbour
    step = sqrt (run ^ 2 + dz .^ 2);  # Delta D and l_k: the 3-D distance between the centres, in cells
    slope_w = slope_weight (slope, slope_table);
    go = ok & slope <= p.climb_deg & slope >= -p.descent_deg;  # slope tabu table (section 2.1)
    go(ok) &= soil_go(to(ok));
    h = zeros (rows, cols);
    h(go) = p.j * slope_w(go) ./ (step(go) + to_goal(to(go)));  # eq. 14
    d = Inf (rows, cols);
    d(go) = step(go) ./ slope_w(go);  # eq. 21's term l_k / slopeW_k
    next(go(:), move) = to(go);
    heuristic(:, move) = h(:);
    distance(:, move) = d(:);
  endfor
  heuristic(heuristic <= 0) = 0;
  next(heuristic == 0) = 0;  # moves whose slopeW is 0 are never taken (H = 0)
endfunction

## slopeW of Table 1 for signed slopes in degrees: the weight of the first row whose upper slope is not below it.
function w = slope_weight (slope, table)
  w = ones (size (slope));
  if (isempty (table))
    return;
  endif
  for row = size (table, 1):-1:1
    w(slope <= table(row, 1)) = table(row, 2);
  endfor
  w(slope > table(end, 1)) = table(end, 2);
endfunction

## Linear index of the cell holding a world point [x, y] (row = y, column = x).
function index = cell_index (point, cell_size, rows)
  index = (floor (point(1) / cell_size)) * rows + floor (point(2) / cell_size) + 1;
endfunction

## World path through the centres of the cells, from exactly the start to exactly the goal.
function path = centre_path (cells, rows, cell_size, start, goal)
  r = mod (cells(:) - 1, rows) + 1;
  c = floor ((cells(:) - 1) / rows) + 1;
  path = ([c, r] - 0.5) * cell_size;
  if (any (path(1, :) != start))
    path = [start; path];
  endif
  if (any (path(end, :) != goal))
    path = [path; goal];
  endif
endfunction
