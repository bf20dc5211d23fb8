!> Penetration audit: the signed distance of surface nodes to the opposite
!> body's faceted surface, from geometry alone. It shares nothing with the
!> search or the enforcement (no pairs, no capture, no depth cut-off, no
!> facing cut), so it sees nodes that the contact dropped or never held.
!> Plain arrays, no MPI, no I/O.
!>
!> Faceting. Each quadrilateral segment (corners P1..P4, counter-clockwise
!> about the outward normal, centre C = mean of the corners) is the four flat
!> triangles T_k = (P_k, P_k+1, C). This is the surface of the contact
!> module's eight facets (their mid-edge points lie in these triangles) and of
!> tools/radial_gap.py.
!>
!> Sign. The closest point q of the faceted surface to a node p lies in a
!> triangle's interior, on an edge or at a vertex. The sign of (p - q) . N,
!> N the angle-weighted pseudo-normal of that feature (a face's normal; the
!> sum of the two normals across an edge; the sum of the incident
!> triangles' normals, each weighted by its angle at a vertex), tells inside
!> from outside exactly for a closed manifold surface (Baerentzen & Aanaes,
!> IEEE TVCG 11 (2005) 243-253). A contact surface is often open (a face set
!> of a body): where q lies on its free boundary and p - q leaves the
!> surface's extent sideways (a component along the surface beyond
!> LATERAL_FRACTION of the segment size), the node is beside the surface, not
!> behind it, and counts as outside. The unit test checks the sign against a
!> brute-force winding number on closed surfaces.
!>
!> Self-contact. A node lies on its own surface, so the segments within two
!> rings of it are not candidates, and a node counts as inside only where
!> the feature faces it (the angle between its own area-weighted normal and
!> N above 120 degrees, SELF_FACING): two folds of one surface meet face to
!> face, while a stretch of surface curving away from the node, even as
!> tightly as the crest of a fold, does not. The rim of the excluded rings
!> is a free edge for the sign test: a node off it sideways is beside the
!> candidate surface (the apex of a fold closed to a V).
!>
!> Reach. Only segments whose box comes within `reach` of a node are
!> candidates (a bucket grid); a node with none gets gap = +reach. A node
!> deeper than `reach` inside the other body is not seen; the callers take
!> reach as a few segment sizes.
!>
!> Tolerance (see node_tolerance): the larger of 5% of the smaller of the
!> node's adjacent segments and the opposite segment, and the opposite
!> segment's faceting sagitta, the distance by which two faceted versions of
!> one curved surface overlap by geometry alone.
module contact_audit
  use core_kinds, only: rk, ik
  use contact_surface, only: contact_surface_t, surface_node_index
  use core_sort, only: sort_values
  use mesh_geometry, only: cross
  implicit none
  private
  public :: audit_gaps, segment_metrics, segment_sizes, closest_on_triangle, node_tolerance
  public :: surface_sagitta, audit_reach
  public :: FEATURE_FACE, SIZE_FRACTION

  !> Feature of a triangle (a, b, c) holding the closest point.
  integer, parameter :: FEATURE_FACE = 0 !< 1, 2, 3: edges ab, bc, ca; 4, 5, 6: vertices a, b, c
  !> Default tolerance: this fraction of the smaller adjacent segment's size.
  real(rk), parameter :: SIZE_FRACTION = 0.05_rk
  !> Neighbouring segments whose normals turn by more than this angle meet at
  !> a crease of the body (a cube's edge, a rod's rim), which the facets
  !> represent exactly: not faceting of a smooth surface, so no sagitta.
  !> 45 degrees: a smooth surface meshed with at least two segments per
  !> quarter turn stays below it, and a right-angled edge is above it.
  real(rk), parameter :: CREASE_ANGLE = 0.7853981633974483_rk
  !> A closest point on a free boundary with a sideways offset beyond this
  !> fraction of the segment size is beside the surface (outside).
  real(rk), parameter :: LATERAL_FRACTION = 1.0e-3_rk
  !> Audit reach in median segment sizes: a node deeper than this inside the
  !> other body is not seen (a zone's worth of penetration is already a
  !> failure of the contact).
  real(rk), parameter :: REACH_SIZES = 3.0_rk
  !> A free edge of the target lies in a symmetry plane when both its ends
  !> are within this fraction of the segment size of the plane (nodes on a
  !> symmetry plane stay on it to round-off).
  real(rk), parameter :: PLANE_FRACTION = 1.0e-9_rk
  !> Self-contact: a node is inside only where its own normal and the
  !> feature's make more than 120 degrees (cosine below this): two sheets
  !> pressed together face each other (cosine near -1), while a surface that
  !> only curves tightly, as at the crest of a fold, turns its normal through
  !> intermediate angles within a few rings of the node.
  real(rk), parameter :: SELF_FACING = -0.5_rk
  !> Largest number of grid cells along one axis.
  integer, parameter :: MAX_CELLS = 64

contains

  !> Closest point q of triangle (a, b, c) to p and the feature holding it:
  !> FEATURE_FACE, 1..3 the edges ab, bc, ca, 4..6 the vertices a, b, c. The
  !> regions follow from the signs of the barycentric coordinates of the
  !> projection and of the edge parameters (Voronoi regions of the triangle).
  pure subroutine closest_on_triangle(p, a, b, c, q, feature)
    real(rk), intent(in) :: p(3), a(3), b(3), c(3)
    real(rk), intent(out) :: q(3)
    integer, intent(out) :: feature
    real(rk) :: ab(3), ac(3), d1, d2, d3, d4, d5, d6, va, vb, vc, t, den

    ab = b - a
    ac = c - a
    d1 = dot_product(ab, p - a)
    d2 = dot_product(ac, p - a)
    if (d1 <= 0.0_rk .and. d2 <= 0.0_rk) then
      q = a
      feature = 4
      return
    end if
    d3 = dot_product(ab, p - b)
    d4 = dot_product(ac, p - b)
    if (d3 >= 0.0_rk .and. d4 <= d3) then
      q = b
      feature = 5
      return
    end if
    vc = d1 * d4 - d3 * d2
    if (vc <= 0.0_rk .and. d1 >= 0.0_rk .and. d3 <= 0.0_rk) then
      t = d1 / (d1 - d3)
      q = a + t * ab
      feature = 1
      return
    end if
    d5 = dot_product(ab, p - c)
    d6 = dot_product(ac, p - c)
    if (d6 >= 0.0_rk .and. d5 <= d6) then
      q = c
      feature = 6
      return
    end if
    vb = d5 * d2 - d1 * d6
    if (vb <= 0.0_rk .and. d2 >= 0.0_rk .and. d6 <= 0.0_rk) then
      t = d2 / (d2 - d6)
      q = a + t * ac
      feature = 3
      return
    end if
    va = d3 * d6 - d5 * d4
    if (va <= 0.0_rk .and. d4 - d3 >= 0.0_rk .and. d5 - d6 >= 0.0_rk) then
      t = (d4 - d3) / ((d4 - d3) + (d5 - d6))
      q = b + t * (c - b)
      feature = 2
      return
    end if
    den = va + vb + vc
    if (.not. den > 0.0_rk) then
      ! Degenerate triangle: its first vertex.
      q = a
      feature = 4
      return
    end if
    q = a + (vb / den) * ab + (vc / den) * ac
    feature = FEATURE_FACE
  end subroutine closest_on_triangle

  !> Per segment: size (square root of the area of its four triangles),
  !> faceting sagitta, and the unit normals and centres of its triangles.
  !> Sagitta: with kappa the largest turn of the segment normal per unit
  !> distance between centres across its edges (theta / |C_s - C_t|), a
  !> surface of that curvature through the corners bulges from the flat
  !> facets by up to kappa L^2 / 8 at the centre, L the longer diagonal
  !> (exact for a sphere: h^2 / (4 R) for a square of side h).
  pure subroutine segment_metrics(x, surf, size, sagitta, centre, tri_normal)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: surf
    real(rk), intent(out) :: size(:), sagitta(:) !< (nseg)
    real(rk), intent(out) :: centre(:, :) !< (3, nseg)
    !> (3, 4, nseg); absent: not kept (triangle_normals gives a segment's)
    real(rk), intent(out), optional :: tri_normal(:, :, :)
    real(rk) :: p(3, 4), qn(3, surf%nseg), kappa, theta, dist, diag, tn(3, 4)
    integer :: s, k, t

    do s = 1, surf%nseg
      call quad_shape(x(:, surf%segments(:, s)), centre(:, s), size(s), qn(:, s), tn)
      if (present(tri_normal)) tri_normal(:, :, s) = tn
    end do
    do s = 1, surf%nseg
      p = x(:, surf%segments(:, s))
      kappa = 0.0_rk
      do k = 1, 4
        t = surf%neighbours(k, s)
        if (t == 0) cycle
        dist = norm2(centre(:, t) - centre(:, s))
        if (.not. dist > 0.0_rk) cycle
        theta = atan2(norm2(cross(qn(:, s), qn(:, t))), dot_product(qn(:, s), qn(:, t)))
        ! A crease (a body's edge), which the facets represent exactly.
        if (theta > CREASE_ANGLE) cycle
        kappa = max(kappa, theta / dist)
      end do
      diag = max(norm2(p(:, 3) - p(:, 1)), norm2(p(:, 4) - p(:, 2)))
      sagitta(s) = 0.125_rk * kappa * diag**2
    end do
  end subroutine segment_metrics

  !> One segment's centre, size, unit normal (of the summed triangle areas)
  !> and triangle unit normals (segment_metrics).
  pure subroutine quad_shape(p, centre, size, normal, tri_normal)
    real(rk), intent(in) :: p(3, 4) !< corners
    real(rk), intent(out) :: centre(3), size, normal(3), tri_normal(3, 4)
    real(rk) :: a(3), area
    integer :: k
    centre = 0.25_rk * (((p(:, 1) + p(:, 2)) + p(:, 3)) + p(:, 4))
    area = 0.0_rk
    normal = 0.0_rk
    do k = 1, 4
      a = cross(p(:, mod(k, 4) + 1) - p(:, k), centre - p(:, k))
      area = area + 0.5_rk * norm2(a)
      normal = normal + a
      tri_normal(:, k) = 0.0_rk
      if (norm2(a) > 0.0_rk) tri_normal(:, k) = a / norm2(a)
    end do
    if (norm2(normal) > 0.0_rk) normal = normal / norm2(normal)
    size = sqrt(area)
  end subroutine quad_shape

  !> The unit normals of segment s's four triangles, as segment_metrics
  !> gives them.
  pure function triangle_normals(x, surf, s) result(tn)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: surf
    integer, intent(in) :: s
    real(rk) :: tn(3, 4), centre(3), size, normal(3)
    call quad_shape(x(:, surf%segments(:, s)), centre, size, normal, tn)
  end function triangle_normals

  !> The size of every segment of a surface, as segment_metrics gives it
  !> (without its other per-segment arrays).
  pure subroutine segment_sizes(x, surf, size)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: surf
    real(rk), intent(out) :: size(:) !< (nseg)
    real(rk) :: centre(3), normal(3), tri_normal(3, 4)
    integer :: s
    do s = 1, surf%nseg
      call quad_shape(x(:, surf%segments(:, s)), centre, size(s), normal, tri_normal)
    end do
  end subroutine segment_sizes

  !> Faceting sagitta of every segment of a surface (see segment_metrics).
  subroutine surface_sagitta(x, surf, sag)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: surf
    real(rk), allocatable, intent(out) :: sag(:)
    real(rk), allocatable :: sz(:), tc(:, :)
    allocate(sag(surf%nseg), sz(surf%nseg), tc(3, surf%nseg))
    call segment_metrics(x, surf, sz, sag, tc)
  end subroutine surface_sagitta

  !> Audit reach of an interface: REACH_SIZES times the larger of the two
  !> surfaces' median segment sizes.
  function audit_reach(x, a, b) result(reach)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: a, b
    real(rk) :: reach
    reach = REACH_SIZES * max(median_size(a), median_size(b), tiny(1.0_rk))
  contains
    real(rk) function median_size(surf) result(h)
      type(contact_surface_t), intent(in) :: surf
      real(rk), allocatable :: sz(:)
      h = 0.0_rk
      if (surf%nseg == 0) return
      allocate(sz(surf%nseg))
      call segment_sizes(x, surf, sz)
      call sort_values(sz)
      h = sz((surf%nseg + 1) / 2)
    end function median_size
  end function audit_reach

  !> Default penetration tolerance of a node: the larger of SIZE_FRACTION of
  !> the smaller of its own smallest adjacent segment (own_size) and the
  !> opposite segment (opp_size), and the opposite segment's sagitta.
  pure real(rk) function node_tolerance(own_size, opp_size, opp_sagitta) result(tol)
    real(rk), intent(in) :: own_size, opp_size, opp_sagitta
    tol = max(SIZE_FRACTION * min(own_size, opp_size), opp_sagitta)
  end function node_tolerance

  !> Signed distances of the selected nodes of `own` to the faceted surface
  !> `target` (> 0 outside the target's body, < 0 inside), with the segment
  !> of the closest point (0: none within reach, gap = reach). x is indexed
  !> by the node numbers of both surfaces. self: own and target are one
  !> surface (self-contact rules above). Deterministic: the grid and the
  !> order in which a node's candidates are visited depend only on the
  !> surfaces and the node, so every rank finds the same closest point (an
  !> exact tie goes to the first visited).
  subroutine audit_gaps(x, own, target, self, reach, selected, gap, hit, inward, planes, &
      target_size, target_sagitta, grid_box)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: own, target
    logical, intent(in) :: self
    real(rk), intent(in) :: reach
    logical, intent(in) :: selected(:) !< (own%nnode) nodes to audit
    real(rk), intent(out) :: gap(:) !< (own%nnode), reach where not selected
    integer, intent(out) :: hit(:) !< (own%nnode)
    real(rk), intent(out) :: inward(:, :) !< (3, own%nnode) unit direction p -> q where inside
    !> (4, n) symmetry planes of the deck, unit normal and offset (n . x =
    !> offset): a free edge of the target lying in one is no edge, the
    !> surface continuing as its mirror image
    real(rk), intent(in), optional :: planes(:, :)
    !> the target's segment sizes and sagittas (segment_metrics), which the
    !> caller's tolerances read (unallocated when no node was audited)
    real(rk), allocatable, intent(out), optional :: target_size(:), target_sagitta(:)
    !> (3, 2) the lower and upper corners of the whole target surface's box
    !> when target is a part of it (the grid is then the whole surface's,
    !> so candidates are visited in the same order; absent: target's own box)
    real(rk), intent(in), optional :: grid_box(:, :)
    real(rk), allocatable :: tsize(:), tsag(:), tc(:, :)
    integer, allocatable :: cell_start(:), cell_list(:), stamp(:), cand(:), ring(:)
    real(rk) :: lo(3), hi(3), cell, p(3), q(3), best_q(3), d2, best_d2, nrm(3), own_n(3), d(3)
    integer :: ncell(3), i, s, k, ncand, best_s, best_k, best_f, f, c1(3), c2(3), ix, iy, iz, &
        j, node, e, m
    logical :: inside
    integer :: nplane

    nplane = 0
    if (present(planes)) nplane = size(planes, 2)
    gap = reach
    hit = 0
    inward = 0.0_rk
    if (target%nseg == 0 .or. own%nnode == 0) return
    ! (triangle normals, read for the closest points' segments only, are
    ! computed there: tnormal)
    allocate(tsize(target%nseg), tsag(target%nseg), tc(3, target%nseg))
    call segment_metrics(x, target, tsize, tsag, tc)
    call build_grid()
    allocate(stamp(target%nseg), cand(target%nseg), ring(target%nseg))
    stamp = 0
    ring = 0
    do i = 1, own%nnode
      if (.not. selected(i)) cycle
      node = own%nodes(i)
      p = x(:, node)
      if (self) call mark_rings(i)
      ! Candidates: segments in the cells within reach.
      c1 = cell_of(p - reach)
      c2 = cell_of(p + reach)
      ncand = 0
      do iz = c1(3), c2(3)
        do iy = c1(2), c2(2)
          do ix = c1(1), c2(1)
            j = ix + ncell(1) * ((iy - 1) + ncell(2) * (iz - 1))
            do e = cell_start(j), cell_start(j + 1) - 1
              s = cell_list(e)
              if (stamp(s) == i) cycle
              stamp(s) = i
              if (self .and. ring(s) == i) cycle
              ncand = ncand + 1
              cand(ncand) = s
            end do
          end do
        end do
      end do
      best_d2 = reach**2
      best_s = 0
      best_k = 0
      best_f = 0
      best_q = p
      do m = 1, ncand
        s = cand(m)
        do k = 1, 4
          call closest_on_triangle(p, x(:, target%segments(k, s)), &
              x(:, target%segments(mod(k, 4) + 1, s)), tc(:, s), q, f)
          d2 = sum((p - q)**2)
          if (d2 < best_d2) then
            best_d2 = d2
            best_s = s
            best_k = k
            best_f = f
            best_q = q
          end if
        end do
      end do
      if (best_s == 0) cycle
      hit(i) = best_s
      gap(i) = sqrt(best_d2)
      call pseudo_normal(best_s, best_k, best_f, nrm, inside)
      d = p - best_q
      inside = inside .and. dot_product(d, nrm) < 0.0_rk
      if (inside .and. self) then
        own_n = node_normal(own, i)
        inside = dot_product(own_n, nrm) < SELF_FACING * norm2(nrm)
      end if
      if (inside) then
        gap(i) = -gap(i)
        if (norm2(d) > 0.0_rk) inward(:, i) = -d / norm2(d)
      end if
    end do
    if (present(target_size)) call move_alloc(tsize, target_size)
    if (present(target_sagitta)) call move_alloc(tsag, target_sagitta)

  contains

    !> Unit normal of triangle k of target segment s (segment_metrics').
    pure function tnormal(k, s) result(n)
      integer, intent(in) :: k, s
      real(rk) :: n(3), tn(3, 4)
      tn = triangle_normals(x, target, s)
      n = tn(:, k)
    end function tnormal

    subroutine build_grid()
      real(rk) :: blo(3), bhi(3)
      integer, allocatable :: fill(:)
      integer :: a1(3), a2(3), jx, jy, jz, jc, total, pass
      if (present(grid_box)) then
        lo = grid_box(:, 1)
        hi = grid_box(:, 2)
      else
        lo = huge(1.0_rk)
        hi = -huge(1.0_rk)
        do s = 1, target%nseg
          do k = 1, 4
            lo = min(lo, x(:, target%segments(k, s)))
            hi = max(hi, x(:, target%segments(k, s)))
          end do
        end do
      end if
      cell = max(reach, maxval(hi - lo) / real(MAX_CELLS, rk), tiny(1.0_rk))
      ncell = max(1, min(MAX_CELLS, int((hi - lo) / cell) + 1))
      total = product(ncell)
      allocate(cell_start(total + 1), fill(total))
      fill = 0
      do pass = 1, 2
          if (pass == 2) then
            cell_start(1) = 1
            do jc = 1, total
              cell_start(jc + 1) = cell_start(jc) + fill(jc)
            end do
            allocate(cell_list(cell_start(total + 1) - 1))
            fill = 0
          end if
          do s = 1, target%nseg
            blo = huge(1.0_rk)
            bhi = -huge(1.0_rk)
            do k = 1, 4
              blo = min(blo, x(:, target%segments(k, s)))
              bhi = max(bhi, x(:, target%segments(k, s)))
            end do
            a1 = cell_of(blo)
            a2 = cell_of(bhi)
            do jz = a1(3), a2(3)
              do jy = a1(2), a2(2)
                do jx = a1(1), a2(1)
                  jc = jx + ncell(1) * ((jy - 1) + ncell(2) * (jz - 1))
                  if (pass == 2) cell_list(cell_start(jc) + fill(jc)) = s
                  fill(jc) = fill(jc) + 1
                end do
              end do
            end do
          end do
        end do
    end subroutine build_grid

    pure function cell_of(point) result(c)
      real(rk), intent(in) :: point(3)
      integer :: c(3)
      c = int((point - lo) / cell) + 1
      c = max(1, min(ncell, c))
    end function cell_of

    !> Mark (ring = i) the segments within two rings of own node i.
    subroutine mark_rings(i)
      integer, intent(in) :: i
      integer :: e1, s1, c, n2, e2
      do e1 = own%node_start(i), own%node_start(i + 1) - 1
        s1 = own%node_segments(e1)
        do c = 1, 4
          n2 = surface_node_index(own, own%segments(c, s1))
          do e2 = own%node_start(n2), own%node_start(n2 + 1) - 1
            ring(own%node_segments(e2)) = i
          end do
        end do
      end do
    end subroutine mark_rings

    !> Pseudo-normal of feature f of triangle k of segment s, and whether
    !> the sign test applies (false: beside a free boundary, outside).
    subroutine pseudo_normal(s, k, f, n, applies)
      integer, intent(in) :: s, k, f
      real(rk), intent(out) :: n(3)
      logical, intent(out) :: applies
      integer :: t, kk, km, vertex_node
      logical :: free
      real(rk) :: lateral(3)
      applies = .true.
      free = .false.
      km = mod(k + 2, 4) + 1
      kk = mod(k, 4) + 1
      select case (f)
      case (FEATURE_FACE)
        n = tnormal(k, s)
      case (1)
        ! Segment edge k (P_k, P_k+1): the neighbour's triangle on it.
        t = target%neighbours(k, s)
        n = tnormal(k, s)
        if (t == 0) then
          ! A free edge, unless it lies in a symmetry plane: then the mirror
          ! image's triangle is across it, n + R n, along the plane.
          free = .not. mirrored(target%segments(k, s), target%segments(kk, s), s, n)
        else
          n = n + tnormal(edge_triangle(t, target%segments(kk, s), target%segments(k, s)), t)
        end if
      case (2)
        ! Edge (P_k+1, C): shared with triangle k+1 of s.
        n = tnormal(k, s) + tnormal(kk, s)
      case (3)
        ! Edge (C, P_k): shared with triangle k-1 of s.
        n = tnormal(k, s) + tnormal(km, s)
      case (6)
        ! The centre: the four triangles, each with its angle there.
        n = 0.0_rk
        do t = 1, 4
          n = n + corner_angle(tc(:, s), x(:, target%segments(t, s)), &
              x(:, target%segments(mod(t, 4) + 1, s))) * tnormal(t, s)
        end do
      case default
        ! A corner node of the segment.
        vertex_node = target%segments(k, s)
        if (f == 5) vertex_node = target%segments(kk, s)
        call vertex_normal(vertex_node, n, free)
      end select
      if (self .and. .not. free) free = excluded_rim(s, k, f)
      if (free .and. norm2(n) > 0.0_rk) then
        n = n / norm2(n)
        lateral = (p - best_q) - dot_product(p - best_q, n) * n
        applies = norm2(lateral) <= LATERAL_FRACTION * tsize(s)
      end if
    end subroutine pseudo_normal

    !> Self-contact: whether feature f of triangle k of segment s lies on the
    !> rim of the rings excluded around node i (a segment edge whose
    !> neighbour across it is excluded, or a corner node of an excluded
    !> segment). The candidate surface ends there as at a free edge: the
    !> surface runs on into the node's own neighbourhood, which is not
    !> judged, so a node off that rim sideways is beside it, not behind it
    !> (the apex of a fold closed to a V lies beyond the rim of its own
    !> flank's third ring and a few degrees behind that segment's plane).
    logical function excluded_rim(s, k, f) result(rim)
      integer, intent(in) :: s, k, f
      integer :: t, vn, e, m
      rim = .false.
      select case (f)
      case (1)
        t = target%neighbours(k, s)
        if (t > 0) rim = ring(t) == i
      case (4, 5)
        vn = target%segments(k, s)
        if (f == 5) vn = target%segments(mod(k, 4) + 1, s)
        m = surface_node_index(target, vn)
        do e = target%node_start(m), target%node_start(m + 1) - 1
          if (ring(target%node_segments(e)) == i) rim = .true.
        end do
      end select
    end function excluded_rim

    !> The triangle of segment t whose segment edge runs from node a to b.
    integer function edge_triangle(t, a, b) result(kt)
      integer, intent(in) :: t
      integer(ik), intent(in) :: a, b
      do kt = 1, 4
        if (target%segments(kt, t) == a .and. target%segments(mod(kt, 4) + 1, t) == b) return
      end do
      do kt = 1, 4
        if (target%segments(kt, t) == b .and. target%segments(mod(kt, 4) + 1, t) == a) return
      end do
      kt = 1
    end function edge_triangle

    !> Angle-weighted normal at a corner node of the target, and whether the
    !> node is on a free edge (one not lying in a symmetry plane; with such
    !> edges only, the mirror images' triangles are added: the normal is
    !> projected on those planes).
    subroutine vertex_normal(vnode, n, free)
      integer(ik), intent(in) :: vnode
      real(rk), intent(out) :: n(3)
      logical, intent(out) :: free
      integer :: iv, e1, s1, c, cp, cm, j
      real(rk) :: dummy(3)
      logical :: on(8)
      n = 0.0_rk
      free = .false.
      on = .false.
      iv = surface_node_index(target, vnode)
      do e1 = target%node_start(iv), target%node_start(iv + 1) - 1
        s1 = target%node_segments(e1)
        c = findloc(target%segments(:, s1), vnode, dim=1)
        cp = mod(c, 4) + 1
        cm = mod(c + 2, 4) + 1
        ! Triangle c = (P_c, P_c+1, C) and triangle c-1 = (P_c-1, P_c, C).
        n = n + corner_angle(x(:, vnode), x(:, target%segments(cp, s1)), tc(:, s1)) * &
            tnormal(c, s1)
        n = n + corner_angle(x(:, vnode), tc(:, s1), x(:, target%segments(cm, s1))) * &
            tnormal(cm, s1)
        dummy = 0.0_rk
        if (target%neighbours(c, s1) == 0) then
          if (.not. mirrored(vnode, target%segments(cp, s1), s1, dummy, on)) free = .true.
        end if
        if (target%neighbours(cm, s1) == 0) then
          if (.not. mirrored(target%segments(cm, s1), vnode, s1, dummy, on)) free = .true.
        end if
      end do
      if (free) return
      do j = 1, min(size(on), nplane)
        if (on(j)) n = n - dot_product(n, planes(1:3, j)) * planes(1:3, j)
      end do
    end subroutine vertex_normal

    !> Whether the edge (a, b) of segment s lies in a symmetry plane (both
    !> ends within PLANE_FRACTION of the segment size of it); if so n is
    !> projected on that plane, and the plane is marked in on.
    logical function mirrored(a, b, s, n, on) result(yes)
      integer(ik), intent(in) :: a, b
      integer, intent(in) :: s
      real(rk), intent(inout) :: n(3)
      logical, intent(inout), optional :: on(:)
      integer :: j
      real(rk) :: tol
      yes = .false.
      tol = PLANE_FRACTION * tsize(s)
      do j = 1, nplane
        if (abs(dot_product(planes(1:3, j), x(:, a)) - planes(4, j)) > tol) cycle
        if (abs(dot_product(planes(1:3, j), x(:, b)) - planes(4, j)) > tol) cycle
        yes = .true.
        n = n - dot_product(n, planes(1:3, j)) * planes(1:3, j)
        if (present(on)) then
          if (j <= size(on)) on(j) = .true.
        end if
      end do
    end function mirrored

    !> Area-weighted unit normal of own node i.
    function node_normal(surf, i) result(n)
      type(contact_surface_t), intent(in) :: surf
      integer, intent(in) :: i
      real(rk) :: n(3), pc(3, 4), cen(3)
      integer :: e1, s1, k1
      n = 0.0_rk
      do e1 = surf%node_start(i), surf%node_start(i + 1) - 1
        s1 = surf%node_segments(e1)
        pc = x(:, surf%segments(:, s1))
        cen = 0.25_rk * (((pc(:, 1) + pc(:, 2)) + pc(:, 3)) + pc(:, 4))
        do k1 = 1, 4
          n = n + cross(pc(:, mod(k1, 4) + 1) - pc(:, k1), cen - pc(:, k1))
        end do
      end do
      if (norm2(n) > 0.0_rk) n = n / norm2(n)
    end function node_normal

  end subroutine audit_gaps

  !> Angle at vertex v of the triangle (v, a, b).
  pure real(rk) function corner_angle(v, a, b) result(angle)
    real(rk), intent(in) :: v(3), a(3), b(3)
    angle = atan2(norm2(cross(a - v, b - v)), dot_product(a - v, b - v))
  end function corner_angle


end module contact_audit
