!> Contact search kernels (plain arrays, no MPI, no I/O): the global bucket /
!> territory search that lists test pairs (node, segment), the local search
!> that finds a node's closest point on a bilinear segment, and the choice of
!> at most one primary pair per slave node.
!>
!> Territory. A segment's territory is the bounding box of its four corners
!> grown by margin in every direction (the largest relative motion before the
!> next search plus the capture tolerance). A node is tested against a segment
!> when it lies in the closed territory.
!>
!> Buckets. Cells of a uniform grid of size h, h the median territory size
!> (largest side of each box), anchored at the low corner of the union of the
!> territories. Each territory is entered in every cell it overlaps as an entry
!> (key, segment), key = i + nx (j + ny k) the cell's linear index; the entries
!> are sorted by key (stable, so segments ascend within a cell), so memory is
!> O(number of entries), not O(cells). A node looks up its own cell by binary
!> search. Cell indices come from floor((p - origin) / h) for the node and for
!> the territory corners alike; correctly rounded arithmetic is monotone, so a
!> node inside a territory always falls in a cell the territory was entered in:
!> the bucket search finds exactly the pairs of the brute-force search.
!>
!> Exclusions. A node never pairs with a segment it belongs to. In self-contact
!> (master and slave the same surface) it does not pair with any segment
!> sharing a node with one of its own segments either (its immediate
!> neighbourhood).
!>
!> Local search. Newton iterations on the bilinear surface x(xi, eta) for the
!> closest point; when Newton fails or leaves [-1, 1]^2 (beyond
!> NATURAL_TOLERANCE), the closest point on the segment's two triangles
!> (1, 2, 3) and (1, 3, 4) is taken instead: their interiors and the diagonal
!> count as the face, the four outer edges and corners as edge / corner. The
!> gap is signed along the outward unit normal of the bilinear surface at the
!> closest point (negative = penetration). At an edge or corner the normal is
!> the closest-point direction, oriented outward (gap >= 0 when the node is on
!> the outer side of the segment).
!>
!> A penetrating node whose normal projection falls just outside the segment
!> (|xi|, |eta| <= 1 + EXTENSION_TOLERANCE) is on the face: a slave node on a
!> symmetry plane lies on the master surface's boundary edge, and once it
!> penetrates a curved master its projection leaves the segment by round-off
!> or by the curvature; classed as an edge or corner it would be rejected
!> (penetrating edge and corner pairs are ambiguous) and sink unchecked
!> (seen on the Taylor rod's axis node, 0.2 cm deep in a steel anvil).
!>
!> Primary pair. Among a node's test pairs that are in contact (contact_kind),
!> the one with the smallest |gap| wins; equal |gap| goes to the lower segment
!> global id (surface%segment_id), so the result does not depend on the order
!> of segments or pairs.
module contact_search
  use core_kinds, only: rk, ik, i8
  use core_sort, only: sort_order, sort_values, find_key => sorted_find
  use contact_surface, only: contact_surface_t, edge_end
  use contact_geometry, only: quad_unit_normal
  implicit none
  private
  public :: segment_territory, bucket_search, closest_point, contact_kind, primary_pairs
  public :: pair_excluded, search_interval, segment_pair_search
  public :: find_key

  !> No contact.
  integer, parameter, public :: KIND_NONE = 0
  !> Node to segment (projection inside the segment).
  integer, parameter, public :: KIND_SEGMENT = 1
  !> Node to (convex) edge.
  integer, parameter, public :: KIND_EDGE = 2
  !> Node to (convex) corner node.
  integer, parameter, public :: KIND_NODE = 3
  !> Closest point inside the segment.
  integer, parameter, public :: LOCATION_FACE = 1
  !> Closest point on an outer edge (local index 1..4).
  integer, parameter, public :: LOCATION_EDGE = 2
  !> Closest point at a corner (local index 1..4).
  integer, parameter, public :: LOCATION_CORNER = 3
  !> A projection with |xi|, |eta| <= 1 + NATURAL_TOLERANCE is inside.
  real(rk), parameter, public :: NATURAL_TOLERANCE = 1.0e-6_rk
  !> A penetrating node's projection within 1 + this is still on the face.
  real(rk), parameter, public :: EXTENSION_TOLERANCE = 0.05_rk
  !> Newton stops when the natural-coordinate step is below this.
  real(rk), parameter :: NEWTON_TOLERANCE = 1.0e-13_rk
  integer, parameter :: NEWTON_MAX = 30
  !> The bucket grid is coarsened until it has fewer cells than this.
  real(rk), parameter :: MAX_CELLS = 1.0e18_rk

  !> The contact pair chosen for one slave node.
  type, public :: primary_pair_t
    integer :: node = 0 !< slave node, global id
    integer :: segment = 0 !< master segment index in its surface
    integer :: kind = KIND_NONE !< KIND_SEGMENT, KIND_EDGE or KIND_NODE
    integer :: local = 0 !< edge or corner 1..4 for KIND_EDGE / KIND_NODE, else 0
    real(rk) :: xi = 0.0_rk !< natural coordinates of the closest point
    real(rk) :: eta = 0.0_rk
    real(rk) :: gap = 0.0_rk !< signed gap, negative = penetration
    real(rk) :: normal(3) = 0.0_rk !< unit contact normal, outward from the master
  end type primary_pair_t

  !> Bucket grid of segment territories: sorted cell keys with a CSR into the
  !> segments (see the module notes).
  type :: bucket_grid_t
    real(rk), allocatable :: lo(:, :), hi(:, :) !< (3, n) territories of the bucketed segments
    real(rk) :: h = 0.0_rk, origin(3) = 0.0_rk, top(3) = 0.0_rk
    integer(i8) :: ncell(3) = 1
    integer(i8), allocatable :: bucket_key(:)
    integer, allocatable :: bucket_start(:), bucket_segment(:)
  end type bucket_grid_t

contains

  !> Territory of one segment: bounding box of its corners grown by margin.
  pure subroutine segment_territory(p, margin, lo, hi)
    real(rk), intent(in) :: p(3, 4) !< corner positions
    real(rk), intent(in) :: margin !< growth in every direction, >= 0
    real(rk), intent(out) :: lo(3), hi(3)
    lo = minval(p, dim=2) - margin
    hi = maxval(p, dim=2) + margin
  end subroutine segment_territory

  !> True when the pair (node, segment) is excluded: the segment holds one of
  !> the excluded nodes (the node itself, or in self-contact the nodes of all
  !> its segments).
  pure logical function pair_excluded(segment, ring)
    integer(ik), intent(in) :: segment(4) !< the segment's global node ids
    integer(ik), intent(in) :: ring(:) !< excluded node ids
    integer :: k
    pair_excluded = .false.
    do k = 1, 4
      if (any(ring == segment(k))) then
        pair_excluded = .true.
        return
      end if
    end do
  end function pair_excluded

  !> Global search: test pairs (slave node, master segment) with the node inside
  !> the segment's territory, sorted by (node global id, segment index).
  !> keys and candidates restrict the search to a subset (an RCB part's slave
  !> nodes, as surface node indices, and the master segments that may reach
  !> them, both ascending); the pairs found among them are exactly those of the
  !> whole search, in the same order.
  subroutine bucket_search(x, slave, master, self_contact, margin, pairs, keys, candidates)
    real(rk), intent(in) :: x(:, :) !< (3, nnode) node positions
    type(contact_surface_t), intent(in) :: slave !< surface whose nodes search
    type(contact_surface_t), intent(in) :: master !< surface whose segments are found
    logical, intent(in) :: self_contact !< slave and master are the same surface
    real(rk), intent(in) :: margin !< territory growth, >= 0
    integer, allocatable, intent(out) :: pairs(:, :) !< (2, npair): node id, segment
    integer, intent(in), optional :: keys(:) !< slave surface nodes to search (default all)
    integer, intent(in), optional :: candidates(:) !< master segments (default all)
    type(bucket_grid_t) :: grid
    integer(ik), allocatable :: ring(:)
    integer, allocatable :: list(:), nodes(:)
    real(rk) :: p(3)
    integer(i8) :: cell(3), key
    integer :: s, n, b, e, npair, node, nring, j, m

    npair = 0
    allocate(pairs(2, 0))
    call subset(master%nseg, list, candidates)
    call subset(slave%nnode, nodes, keys)
    if (size(list) == 0 .or. size(nodes) == 0) return
    call build_buckets(x, master, list, margin, grid)

    ! Each slave node looks in its own bucket.
    allocate(ring(4 * maxval(slave%node_start(2:) - slave%node_start(:slave%nnode))))
    do m = 1, size(nodes)
      n = nodes(m)
      node = slave%nodes(n)
      p = x(:, node)
      if (any(p < grid%origin) .or. any(p > grid%top)) cycle
      cell = grid_cell(grid, p)
      key = cell(1) + grid%ncell(1) * (cell(2) + grid%ncell(2) * cell(3))
      b = find_key(grid%bucket_key, key)
      if (b == 0) cycle
      call node_ring(slave, n, self_contact, ring, nring)
      do e = grid%bucket_start(b), grid%bucket_start(b + 1) - 1
        j = grid%bucket_segment(e)
        s = list(j)
        if (any(p < grid%lo(:, j)) .or. any(p > grid%hi(:, j))) cycle
        if (pair_excluded(master%segments(:, s), ring(:nring))) cycle
        call append_pair(pairs, npair, node, s)
      end do
    end do
    pairs = pairs(:, :npair)
  end subroutine bucket_search

  !> Global search for segment pairs: (a, b), a a segment of surf_a and b one of
  !> surf_b, with a's bounding box overlapping b's territory (grown by margin).
  !> Sorted by (a, b). In self-contact (the same surface twice) each pair is
  !> listed once, a < b, and segments sharing a node are never paired.
  !> keys (segments of a) and candidates (segments of b), both ascending,
  !> restrict the search to a subset, as in bucket_search.
  subroutine segment_pair_search(x, surf_a, surf_b, self_contact, margin, pairs, keys, &
      candidates)
    real(rk), intent(in) :: x(:, :) !< (3, nnode) node positions
    type(contact_surface_t), intent(in) :: surf_a, surf_b
    logical, intent(in) :: self_contact
    real(rk), intent(in) :: margin !< territory growth of surf_b's segments, >= 0
    integer, allocatable, intent(out) :: pairs(:, :) !< (2, npair): segment of a, of b
    integer, intent(in), optional :: keys(:) !< segments of a to search (default all)
    integer, intent(in), optional :: candidates(:) !< segments of b (default all)
    type(bucket_grid_t) :: grid
    integer, allocatable :: mark(:), list(:), segs(:)
    real(rk) :: lo(3), hi(3)
    integer(i8) :: cell_lo(3), cell_hi(3), i, j, k, key
    integer :: sa, sb, b, e, npair, first, jb, ma

    npair = 0
    allocate(pairs(2, 0))
    call subset(surf_b%nseg, list, candidates)
    call subset(surf_a%nseg, segs, keys)
    if (size(list) == 0 .or. size(segs) == 0) return
    call build_buckets(x, surf_b, list, margin, grid)
    allocate(mark(size(list)))
    mark = 0
    do ma = 1, size(segs)
      sa = segs(ma)
      call segment_territory(x(:, surf_a%segments(:, sa)), 0.0_rk, lo, hi)
      if (any(hi < grid%origin) .or. any(lo > grid%top)) cycle
      first = npair + 1
      cell_lo = grid_cell(grid, lo)
      cell_hi = grid_cell(grid, hi)
      do k = cell_lo(3), cell_hi(3)
        do j = cell_lo(2), cell_hi(2)
          do i = cell_lo(1), cell_hi(1)
            key = i + grid%ncell(1) * (j + grid%ncell(2) * k)
            b = find_key(grid%bucket_key, key)
            if (b == 0) cycle
            do e = grid%bucket_start(b), grid%bucket_start(b + 1) - 1
              jb = grid%bucket_segment(e)
              if (mark(jb) == sa) cycle
              mark(jb) = sa
              sb = list(jb)
              if (any(hi < grid%lo(:, jb)) .or. any(lo > grid%hi(:, jb))) cycle
              if (self_contact) then
                if (sb <= sa) cycle
                if (pair_excluded(surf_b%segments(:, sb), surf_a%segments(:, sa))) cycle
              end if
              call append_pair(pairs, npair, sa, sb)
            end do
          end do
        end do
      end do
      ! Ascending b within a.
      call sort_values(pairs(2, first:npair))
    end do
    pairs = pairs(:, :npair)
  end subroutine segment_pair_search

  !> The given subset, or 1..n when absent.
  pure subroutine subset(n, list, given)
    integer, intent(in) :: n
    integer, allocatable, intent(out) :: list(:)
    integer, intent(in), optional :: given(:)
    integer :: i
    if (present(given)) then
      list = given
    else
      list = [(i, i = 1, n)]
    end if
  end subroutine subset

  !> Buckets of the territories of the master segments (see the module notes).
  !> Entries refer to positions in list (the segments bucketed).
  subroutine build_buckets(x, master, list, margin, g)
    real(rk), intent(in) :: x(:, :) !< (3, nnode) node positions
    type(contact_surface_t), intent(in) :: master
    integer, intent(in) :: list(:) !< the master segments to bucket
    real(rk), intent(in) :: margin !< territory growth, >= 0
    type(bucket_grid_t), intent(out) :: g
    real(rk), allocatable :: sizes(:)
    integer(i8), allocatable :: entry_key(:)
    integer, allocatable :: entry_segment(:), perm(:)
    integer(i8) :: cell_lo(3), cell_hi(3), nentry, i, j, k
    integer :: nseg, s, nbucket, m
    nseg = size(list)
    allocate(g%lo(3, nseg), g%hi(3, nseg), sizes(nseg))
    do s = 1, nseg
      call segment_territory(x(:, master%segments(:, list(s))), margin, g%lo(:, s), g%hi(:, s))
      sizes(s) = maxval(g%hi(:, s) - g%lo(:, s))
    end do
    call sort_values(sizes)
    g%h = sizes((nseg + 1) / 2)
    g%origin = minval(g%lo, dim=2)
    g%top = maxval(g%hi, dim=2)
    if (.not. g%h > 0.0_rk) g%h = max(maxval(g%top - g%origin), 1.0_rk)
    do
      g%ncell = floor((g%top - g%origin) / g%h, i8) + 1_i8
      if (product(real(g%ncell, rk)) < MAX_CELLS) exit
      g%h = 2.0_rk * g%h
    end do

    ! Entries (cell key, segment) for every cell each territory overlaps.
    nentry = 0
    do s = 1, nseg
      cell_lo = grid_cell(g, g%lo(:, s))
      cell_hi = grid_cell(g, g%hi(:, s))
      nentry = nentry + product(cell_hi - cell_lo + 1_i8)
    end do
    allocate(entry_key(nentry), entry_segment(nentry))
    nentry = 0
    do s = 1, nseg
      cell_lo = grid_cell(g, g%lo(:, s))
      cell_hi = grid_cell(g, g%hi(:, s))
      do k = cell_lo(3), cell_hi(3)
        do j = cell_lo(2), cell_hi(2)
          do i = cell_lo(1), cell_hi(1)
            nentry = nentry + 1
            entry_key(nentry) = i + g%ncell(1) * (j + g%ncell(2) * k)
            entry_segment(nentry) = s
          end do
        end do
      end do
    end do
    call sort_order(entry_key, perm)

    ! Buckets: distinct keys with a CSR into the segments.
    nbucket = 0
    do m = 1, int(nentry)
      if (m == 1) then
        nbucket = 1
      else if (entry_key(perm(m)) /= entry_key(perm(m - 1))) then
        nbucket = nbucket + 1
      end if
    end do
    allocate(g%bucket_key(nbucket), g%bucket_start(nbucket + 1), g%bucket_segment(nentry))
    nbucket = 0
    do m = 1, int(nentry)
      if (m == 1) then
        nbucket = 1
        g%bucket_key(1) = entry_key(perm(1))
        g%bucket_start(1) = 1
      else if (entry_key(perm(m)) /= entry_key(perm(m - 1))) then
        nbucket = nbucket + 1
        g%bucket_key(nbucket) = entry_key(perm(m))
        g%bucket_start(nbucket) = m
      end if
      g%bucket_segment(m) = entry_segment(perm(m))
    end do
    g%bucket_start(nbucket + 1) = int(nentry) + 1
    deallocate(entry_key, entry_segment, perm)

  end subroutine build_buckets

  !> Cell of a point, clamped to the grid.
  pure function grid_cell(g, point) result(c)
    type(bucket_grid_t), intent(in) :: g
    real(rk), intent(in) :: point(3)
    integer(i8) :: c(3)
    c = min(max(floor((point - g%origin) / g%h, i8), 0_i8), g%ncell - 1_i8)
  end function grid_cell


  !> Excluded nodes of surface node n: itself, and in self-contact every node
  !> of its segments.
  pure subroutine node_ring(surf, n, self_contact, ring, nring)
    type(contact_surface_t), intent(in) :: surf
    integer, intent(in) :: n !< local node index in surf
    logical, intent(in) :: self_contact
    integer(ik), intent(inout) :: ring(:)
    integer, intent(out) :: nring
    integer :: i
    if (self_contact) then
      nring = 0
      do i = surf%node_start(n), surf%node_start(n + 1) - 1
        ring(nring + 1:nring + 4) = surf%segments(:, surf%node_segments(i))
        nring = nring + 4
      end do
    else
      nring = 1
      ring(1) = surf%nodes(n)
    end if
  end subroutine node_ring

  !> Append (node, segment), doubling the storage when full.
  pure subroutine append_pair(pairs, npair, node, segment)
    integer, allocatable, intent(inout) :: pairs(:, :)
    integer, intent(inout) :: npair
    integer, intent(in) :: node, segment
    integer, allocatable :: grown(:, :)
    if (npair == size(pairs, 2)) then
      allocate(grown(2, max(16, 2 * npair)))
      grown(:, :npair) = pairs(:, :npair)
      call move_alloc(grown, pairs)
    end if
    npair = npair + 1
    pairs(:, npair) = [node, segment]
  end subroutine append_pair


  !> Closest point of node q on the bilinear segment p (see the module notes).
  pure subroutine closest_point(p, q, xi, eta, gap, normal, location, local)
    real(rk), intent(in) :: p(3, 4) !< corners, counter-clockwise about the outward normal
    real(rk), intent(in) :: q(3) !< node position
    real(rk), intent(out) :: xi, eta !< natural coordinates of the closest point
    real(rk), intent(out) :: gap !< signed gap along normal, negative = penetration
    real(rk), intent(out) :: normal(3) !< unit contact normal (outward)
    integer, intent(out) :: location !< LOCATION_FACE, LOCATION_EDGE or LOCATION_CORNER
    integer, intent(out) :: local !< edge or corner index 1..4 (0 on the face)
    real(rk) :: centre(3), a(3), b(3), d(3), point(3), r(3), tangent_xi(3), tangent_eta(3)
    real(rk) :: f1, f2, h11, h12, h22, det, step_xi, step_eta, distance, reference(3)
    logical :: converged
    integer :: iteration

    centre = 0.25_rk * (p(:, 1) + p(:, 2) + p(:, 3) + p(:, 4))
    a = 0.25_rk * (-p(:, 1) + p(:, 2) + p(:, 3) - p(:, 4))
    b = 0.25_rk * (-p(:, 1) - p(:, 2) + p(:, 3) + p(:, 4))
    d = 0.25_rk * (p(:, 1) - p(:, 2) + p(:, 3) - p(:, 4))
    xi = 0.0_rk
    eta = 0.0_rk
    converged = .false.
    do iteration = 1, NEWTON_MAX
      r = centre + xi * a + eta * b + xi * eta * d - q
      tangent_xi = a + eta * d
      tangent_eta = b + xi * d
      f1 = dot_product(r, tangent_xi)
      f2 = dot_product(r, tangent_eta)
      h11 = dot_product(tangent_xi, tangent_xi)
      h22 = dot_product(tangent_eta, tangent_eta)
      h12 = dot_product(tangent_xi, tangent_eta) + dot_product(r, d)
      det = h11 * h22 - h12 * h12
      if (.not. det > 1.0e-12_rk * h11 * h22) then
        ! Not a minimum direction: fall back to Gauss-Newton.
        h12 = dot_product(tangent_xi, tangent_eta)
        det = h11 * h22 - h12 * h12
        if (.not. det > 1.0e-12_rk * h11 * h22) exit
      end if
      step_xi = -(h22 * f1 - h12 * f2) / det
      step_eta = -(h11 * f2 - h12 * f1) / det
      xi = xi + step_xi
      eta = eta + step_eta
      if (abs(xi) > 10.0_rk .or. abs(eta) > 10.0_rk) exit
      if (max(abs(step_xi), abs(step_eta)) < NEWTON_TOLERANCE) then
        converged = .true.
        exit
      end if
    end do
    if (converged .and. max(abs(xi), abs(eta)) <= 1.0_rk + EXTENSION_TOLERANCE) then
      reference = bilinear_normal(xi, eta)
      if (any(reference /= 0.0_rk)) then
        point = centre + xi * a + eta * b + xi * eta * d
        gap = dot_product(q - point, reference)
        if (max(abs(xi), abs(eta)) <= 1.0_rk + NATURAL_TOLERANCE .or. gap < 0.0_rk) then
          location = LOCATION_FACE
          local = 0
          normal = reference
          return
        end if
      end if
    end if

    call closest_on_triangles(p, q, point, xi, eta, location, local)
    reference = bilinear_normal(xi, eta)
    if (all(reference == 0.0_rk)) reference = quad_unit_normal(p)
    if (location == LOCATION_FACE) then
      normal = reference
      gap = dot_product(q - point, normal)
    else
      r = q - point
      distance = norm2(r)
      if (distance > 0.0_rk) then
        normal = r / distance
        gap = distance
        if (dot_product(r, reference) < 0.0_rk) then
          normal = -normal
          gap = -distance
        end if
      else
        normal = reference
        gap = 0.0_rk
      end if
    end if

  contains

    pure function bilinear_normal(u, v) result(unit)
      real(rk), intent(in) :: u, v
      real(rk) :: unit(3), tu(3), tv(3), length
      tu = a + v * d
      tv = b + u * d
      unit = [tu(2) * tv(3) - tu(3) * tv(2), tu(3) * tv(1) - tu(1) * tv(3), &
          tu(1) * tv(2) - tu(2) * tv(1)]
      length = norm2(unit)
      if (length > 0.0_rk) then
        unit = unit / length
      else
        unit = 0.0_rk
      end if
    end function bilinear_normal

  end subroutine closest_point

  !> Closest point of q on the triangles (1, 2, 3) and (1, 3, 4) of a segment:
  !> interiors and the diagonal are the face, outer edges and corners are edges
  !> and corners. Ties go to the first candidate (triangles, edges 1..4, diagonal).
  pure subroutine closest_on_triangles(p, q, point, xi, eta, location, local)
    real(rk), intent(in) :: p(3, 4), q(3)
    real(rk), intent(out) :: point(3), xi, eta
    integer, intent(out) :: location, local
    integer, parameter :: TRIANGLE(3, 2) = reshape([1, 2, 3, 1, 3, 4], [3, 2])
    real(rk) :: best, e1(3), e2(3), w(3), plane(3), nn, u, v, candidate(3), dist2, t, e(3)
    real(rk) :: ee
    integer :: m, k, ka, kb

    best = huge(1.0_rk)
    point = p(:, 1)
    xi = -1.0_rk
    eta = -1.0_rk
    location = LOCATION_CORNER
    local = 1
    do m = 1, 2
      e1 = p(:, TRIANGLE(2, m)) - p(:, TRIANGLE(1, m))
      e2 = p(:, TRIANGLE(3, m)) - p(:, TRIANGLE(1, m))
      plane = cross(e1, e2)
      nn = dot_product(plane, plane)
      if (.not. nn > 0.0_rk) cycle
      w = q - p(:, TRIANGLE(1, m))
      u = dot_product(cross(w, e2), plane) / nn
      v = dot_product(cross(e1, w), plane) / nn
      if (u < 0.0_rk .or. v < 0.0_rk .or. u + v > 1.0_rk) cycle
      candidate = p(:, TRIANGLE(1, m)) + u * e1 + v * e2
      dist2 = sum((q - candidate)**2)
      if (dist2 < best) then
        best = dist2
        point = candidate
        location = LOCATION_FACE
        local = 0
        if (m == 1) then
          xi = -(1.0_rk - u - v) + u + v
          eta = -(1.0_rk - u - v) - u + v
        else
          xi = -(1.0_rk - u - v) + u - v
          eta = -(1.0_rk - u - v) + u + v
        end if
      end if
    end do
    do k = 1, 5
      if (k <= 4) then
        ka = k
        kb = edge_end(k)
      else
        ka = 1
        kb = 3
      end if
      e = p(:, kb) - p(:, ka)
      ee = dot_product(e, e)
      t = 0.0_rk
      if (ee > 0.0_rk) t = min(max(dot_product(q - p(:, ka), e) / ee, 0.0_rk), 1.0_rk)
      ! The diagonal's ends are corners, found as such by the outer edges.
      if (k == 5 .and. (t == 0.0_rk .or. t == 1.0_rk)) cycle
      if (t == 1.0_rk) then
        candidate = p(:, kb)
      else
        candidate = p(:, ka) + t * e
      end if
      dist2 = sum((q - candidate)**2)
      if (.not. dist2 < best) cycle
      best = dist2
      point = candidate
      if (k == 5) then
        location = LOCATION_FACE
        local = 0
        xi = -1.0_rk + 2.0_rk * t
        eta = xi
        cycle
      end if
      select case (k)
      case (1)
        xi = -1.0_rk + 2.0_rk * t
        eta = -1.0_rk
      case (2)
        xi = 1.0_rk
        eta = -1.0_rk + 2.0_rk * t
      case (3)
        xi = 1.0_rk - 2.0_rk * t
        eta = 1.0_rk
      case default
        xi = -1.0_rk
        eta = 1.0_rk - 2.0_rk * t
      end select
      if (t == 0.0_rk) then
        location = LOCATION_CORNER
        local = ka
      else if (t == 1.0_rk) then
        location = LOCATION_CORNER
        local = kb
      else
        location = LOCATION_EDGE
        local = k
      end if
    end do
  end subroutine closest_on_triangles

  !> Kind of contact of a local-search result: a face point with
  !> -depth < gap < capture is KIND_SEGMENT; an edge point on a convex edge, or a
  !> corner point whose two edges are convex, with 0 <= gap < capture is
  !> KIND_EDGE / KIND_NODE; anything else KIND_NONE.
  pure integer function contact_kind(location, local, gap, edge_convex, capture, depth) &
      result(kind)
    integer, intent(in) :: location !< from closest_point
    integer, intent(in) :: local !< from closest_point
    real(rk), intent(in) :: gap !< from closest_point
    logical, intent(in) :: edge_convex(4) !< the segment's edge flags
    real(rk), intent(in) :: capture !< capture tolerance (largest open gap)
    real(rk), intent(in) :: depth !< largest accepted penetration
    kind = KIND_NONE
    select case (location)
    case (LOCATION_FACE)
      if (gap < capture .and. gap > -depth) kind = KIND_SEGMENT
    case (LOCATION_EDGE)
      if (edge_convex(local) .and. gap >= 0.0_rk .and. gap < capture) kind = KIND_EDGE
    case (LOCATION_CORNER)
      if (edge_convex(local) .and. edge_convex(mod(local + 2, 4) + 1) .and. &
          gap >= 0.0_rk .and. gap < capture) kind = KIND_NODE
    end select
  end function contact_kind

  !> At most one primary pair per slave node from the test pairs (sorted by node,
  !> as bucket_search returns them): smallest |gap|, then lowest segment id.
  subroutine primary_pairs(x, master, pairs, capture, depth, primary, kept)
    real(rk), intent(in) :: x(:, :) !< (3, nnode) node positions
    type(contact_surface_t), intent(in) :: master
    integer, intent(in) :: pairs(:, :) !< (2, npair) node id, segment; grouped by node
    real(rk), intent(in) :: capture !< capture tolerance (largest open gap)
    real(rk), intent(in) :: depth !< largest accepted penetration
    !> (nnode) initial penetration kept per node: accepted on top of depth
    real(rk), intent(in), optional :: kept(:)
    type(primary_pair_t), allocatable, intent(out) :: primary(:)
    type(primary_pair_t) :: best, trial
    integer :: m, count_primary, s, location, previous_node

    allocate(primary(size(pairs, 2)))
    previous_node = -huge(1)
    count_primary = 0
    best%kind = KIND_NONE
    do m = 1, size(pairs, 2)
      if (pairs(1, m) /= previous_node) call flush_best()
      previous_node = pairs(1, m)
      s = pairs(2, m)
      trial%node = pairs(1, m)
      trial%segment = s
      call closest_point(x(:, master%segments(:, s)), x(:, pairs(1, m)), trial%xi, trial%eta, &
          trial%gap, trial%normal, location, trial%local)
      if (present(kept)) then
        trial%kind = contact_kind(location, trial%local, trial%gap, master%edge_convex(:, s), &
            capture, depth + kept(pairs(1, m)))
      else
        trial%kind = contact_kind(location, trial%local, trial%gap, master%edge_convex(:, s), &
            capture, depth)
      end if
      if (trial%kind == KIND_NONE) cycle
      if (best%kind == KIND_NONE) then
        best = trial
      else if (abs(trial%gap) < abs(best%gap) .or. (abs(trial%gap) == abs(best%gap) .and. &
          master%segment_id(s) < master%segment_id(best%segment))) then
        best = trial
      end if
    end do
    call flush_best()
    primary = primary(:count_primary)

  contains

    subroutine flush_best()
      if (best%kind /= KIND_NONE) then
        count_primary = count_primary + 1
        primary(count_primary) = best
      end if
      best%kind = KIND_NONE
    end subroutine flush_best

  end subroutine primary_pairs

  pure function cross(u, v) result(w)
    real(rk), intent(in) :: u(3), v(3)
    real(rk) :: w(3)
    w(1) = u(2) * v(3) - u(3) * v(2)
    w(2) = u(3) * v(1) - u(1) * v(3)
    w(3) = u(1) * v(2) - u(2) * v(1)
  end function cross

  !> Cycles between global searches such that no contact is missed: a node and
  !> a segment close at most at the relative speed `speed`; with a factor 2 of
  !> safety for acceleration and dt growing by dt_growth per cycle, k is the
  !> largest number of steps whose accumulated closing distance stays within
  !> the margin left after the capture tolerance, so every pair that can touch
  !> before the next search is already a test pair. k >= 1 (1 when the margin
  !> is used up), at most max_interval (also when nothing moves).
  pure function search_interval(margin, capture, speed, dt, dt_growth, max_interval) result(k)
    real(rk), intent(in) :: margin !< territory margin of the last search
    real(rk), intent(in) :: capture !< capture tolerance (part of the margin)
    real(rk), intent(in) :: speed !< largest relative closing speed
    real(rk), intent(in) :: dt !< current step
    real(rk), intent(in) :: dt_growth !< largest growth of dt per cycle (>= 1)
    integer, intent(in) :: max_interval
    integer :: k
    real(rk) :: room, travelled, step
    room = margin - capture
    if (room <= 0.0_rk) then
      k = 1
      return
    end if
    if (speed <= 0.0_rk) then
      k = max_interval
      return
    end if
    k = 0
    travelled = 0.0_rk
    step = dt
    do while (k < max_interval)
      step = step * dt_growth
      travelled = travelled + 2.0_rk * speed * step
      if (travelled > room) exit
      k = k + 1
    end do
    k = max(1, k)
  end function search_interval

end module contact_search
