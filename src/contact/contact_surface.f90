!> Contact surfaces: the quadrilateral segments of one or more face sets of the
!> global mesh, their nodes, node -> segment adjacency, neighbours across edges
!> and a convex/concave flag per edge.
!>
!> Segments keep the outward node order of mesh_geometry's HEX_FACE_NODES
!> (counter-clockwise about the outward normal). Edge k of a segment runs from
!> its corner k to corner mod(k, 4) + 1. Node positions are not stored: they are
!> passed as x(3, nnode) of the mesh, so a surface is built once and reused
!> every cycle (only surface_update_edges depends on positions).
!>
!> Convexity. For edge k of segment s (direction e, from corner k to k+1) with
!> neighbour t across it, the edge is convex when (n_s x n_t) . e > 0, n_s and
!> n_t the unit outward normals of the two segments (on a box, a top face and a
!> side face meet at a convex edge). The expression is exactly antisymmetric
!> in (s, t) and e, so both sides of an edge agree bitwise. Edges that are flat
!> to within CONVEX_TOLERANCE, and concave edges, are not convex; free edges
!> (no neighbour) count as convex. Where more than two segments share an edge,
!> the neighbour is the lowest-numbered other one.
module contact_surface
  use core_kinds, only: rk, ik, i8
  use core_sort, only: sort_values, sort_unique, sorted_find
  use core_status, only: status_t
  use mesh_geometry, only: HEX_FACE_NODES
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_local, only: mesh_t
  use contact_geometry, only: quad_unit_normal, corner_areas
  implicit none
  private
  public :: surface_build, surface_from_segments, surface_update_edges, set_names_of
  public :: surface_renumbered, surface_relabelled
  public :: contact_surface_rebuild
  public :: surface_node_index, edge_end
  public :: ring_of, local_surface, master_neighbourhood, keep_lower_side, nodal_areas

  !> An edge is convex when sin(angle between the segment normals) exceeds this.
  real(rk), parameter, public :: CONVEX_TOLERANCE = 1.0e-8_rk

  !> Segments of a contact surface with their adjacency.
  type, public :: contact_surface_t
    integer :: nseg = 0 !< number of segments
    integer(ik), allocatable :: segments(:, :) !< (4, nseg) global node ids, outward order
    !> (nseg) global face id (zone - 1) * 6 + face, fixed under relabelling
    integer(i8), allocatable :: segment_id(:)
    integer :: nnode = 0 !< number of surface nodes
    integer(ik), allocatable :: nodes(:) !< (nnode) sorted global node ids
    integer, allocatable :: node_start(:) !< (nnode + 1) CSR into node_segments
    integer, allocatable :: node_segments(:) !< segments of each node, ascending
    integer, allocatable :: neighbours(:, :) !< (4, nseg) segment across edge k, 0 if free
    logical, allocatable :: edge_convex(:, :) !< (4, nseg) edge k is convex (or free)
  contains
    procedure :: free => contact_surface_free
  end type contact_surface_t

contains

  !> Release everything.
  subroutine contact_surface_free(this)
    class(contact_surface_t), intent(inout) :: this
    if (allocated(this%segments)) deallocate(this%segments)
    if (allocated(this%segment_id)) deallocate(this%segment_id)
    if (allocated(this%nodes)) deallocate(this%nodes)
    if (allocated(this%node_start)) deallocate(this%node_start)
    if (allocated(this%node_segments)) deallocate(this%node_segments)
    if (allocated(this%neighbours)) deallocate(this%neighbours)
    if (allocated(this%edge_convex)) deallocate(this%edge_convex)
    this%nseg = 0
    this%nnode = 0
  end subroutine contact_surface_free

  !> Local index of corner k's successor along the segment boundary.
  elemental integer function edge_end(k)
    integer, intent(in) :: k !< corner / edge index 1..4
    edge_end = mod(k, 4) + 1
  end function edge_end

  !> The face-set names of a deck's surface list: names separated by blanks
  !> or commas ('left_xmax, right_xmin').
  pure function set_names_of(list) result(names)
    character(len=*), intent(in) :: list
    character(len=NAME_LEN), allocatable :: names(:)
    integer :: pass, i, start, n, count
    logical :: separator
    n = len_trim(list)
    do pass = 1, 2
      count = 0
      start = 0
      do i = 1, n + 1
        separator = i > n
        if (.not. separator) separator = list(i:i) == ' ' .or. list(i:i) == ','
        if (.not. separator) then
          if (start == 0) start = i
        else if (start > 0) then
          count = count + 1
          if (pass == 2) names(count) = list(start:i - 1)
          start = 0
        end if
      end do
      if (pass == 1) allocate(names(count))
    end do
  end function set_names_of

  !> Build a surface from named face sets of the mesh (in the order given);
  !> convexity uses the mesh coordinates. Unknown names are reported in status.
  subroutine surface_build(mesh, set_names, surf, status)
    type(global_mesh_t), intent(in) :: mesh
    character(len=*), intent(in) :: set_names(:) !< face sets forming the surface
    type(contact_surface_t), intent(inout) :: surf
    type(status_t), intent(inout) :: status
    integer(ik), allocatable :: segments(:, :)
    integer(i8), allocatable :: ids(:)
    integer :: i, k, f, count_face, zone, face, nbad

    call surf%free()
    nbad = 0
    count_face = 0
    do i = 1, size(set_names)
      k = mesh%find_set(set_names(i))
      if (k == 0) then
        call status%add("contact surface: no face set '" // trim(set_names(i)) // &
            "' in the mesh; valid sets: " // set_list())
        nbad = nbad + 1
      else
        count_face = count_face + mesh%set_start(k + 1) - mesh%set_start(k)
      end if
    end do
    if (nbad > 0) return
    allocate(segments(4, count_face), ids(count_face))
    count_face = 0
    do i = 1, size(set_names)
      k = mesh%find_set(set_names(i))
      do f = mesh%set_start(k), mesh%set_start(k + 1) - 1
        count_face = count_face + 1
        zone = mesh%set_zone(f)
        face = mesh%set_face(f)
        segments(:, count_face) = mesh%connectivity(HEX_FACE_NODES(:, face), zone)
        ids(count_face) = int(zone - 1, i8) * 6_i8 + int(face, i8)
      end do
    end do
    call surface_from_segments(segments, ids, mesh%coordinates, surf)

  contains

    function set_list() result(text)
      character(len=:), allocatable :: text
      integer :: j
      text = ''
      do j = 1, mesh%nset
        if (j > 1) text = text // ', '
        text = text // trim(mesh%set_name(j))
      end do
    end function set_list

  end subroutine surface_build

  !> The exterior faces of the live zones of the given blocks among this
  !> rank's owned zones, from the local mesh only: each face of the whole
  !> mesh is found by exactly one rank, the owner of its zone. A face is
  !> exterior when across it there is no zone (the mesh boundary), a zone
  !> that is not live, or a live zone of a block in facing (the two blocks
  !> are the sides of a contact pair); a face between two zones of blocks is
  !> interior, and the faces of the local face sets in excluded (symmetry
  !> planes, rigid walls) are left out. live covers the ghost zones too (the
  !> caller refreshes them through the zone halo). Faces come out in
  !> ascending id, the order of the owned zones' global ids.
  subroutine contact_surface_rebuild(mesh, live, blocks, facing, excluded, ids, nodes)
    type(mesh_t), intent(in) :: mesh
    logical, intent(in) :: live(:) !< (nzone) local zones, ghosts included
    integer, intent(in) :: blocks(:) !< block indices of the surface
    integer, intent(in) :: facing(:) !< block indices across which a face is exterior
    integer, intent(in) :: excluded(:) !< local face sets (mesh%set_*) left out
    integer(i8), allocatable, intent(out) :: ids(:) !< (n) (zone gid - 1) * 6 + face
    integer(i8), allocatable, intent(out) :: nodes(:, :) !< (4, n) global node ids, outward
    logical, allocatable :: closed(:, :)
    integer :: z, f, nb, i, j, n, pass
    logical :: exterior
    ! Faces of the excluded sets, per owned zone.
    allocate(closed(6, mesh%nzone))
    closed = .false.
    do i = 1, size(excluded)
      do j = mesh%set_start(excluded(i)), mesh%set_start(excluded(i) + 1) - 1
        closed(mesh%set_face(j), mesh%set_zone(j)) = .true.
      end do
    end do
    do pass = 1, 2
      n = 0
      do z = 1, mesh%nzone_owned
        if (.not. live(z)) cycle
        if (.not. any(blocks == mesh%zone_block(z))) cycle
        do f = 1, 6
          if (closed(f, z)) cycle
          nb = mesh%face_neighbour(f, z)
          if (nb < 0) error stop 'contact_surface_rebuild: a face neighbour of an owned zone '// &
              'is not local'
          if (nb == 0) then
            exterior = .true.
          else if (.not. live(nb)) then
            exterior = .true.
          else
            exterior = any(facing == mesh%zone_block(nb))
          end if
          if (.not. exterior) cycle
          n = n + 1
          if (pass == 1) cycle
          ids(n) = (mesh%zone_gid(z) - 1_i8) * 6_i8 + int(f, i8)
          nodes(:, n) = mesh%node_gid(mesh%zone_node(HEX_FACE_NODES(:, f), z))
        end do
      end do
      if (pass == 1) allocate(ids(n), nodes(4, n))
    end do
  end subroutine contact_surface_rebuild

  !> Build a surface from an explicit segment list (outward node order).
  subroutine surface_from_segments(segments, segment_id, x, surf, adjacent)
    integer(ik), intent(in) :: segments(:, :) !< (4, nseg) global node ids
    integer(i8), intent(in) :: segment_id(:) !< (nseg) global ids, for tie-breaking
    !> (3, nnode) node positions (absent: no edge flags, every edge convex)
    real(rk), intent(in), optional :: x(:, :)
    type(contact_surface_t), intent(inout) :: surf
    !> .false.: no neighbours across edges and no edge flags (a surface
    !> that only the search reads)
    logical, intent(in), optional :: adjacent
    integer, allocatable :: local(:, :), fill(:)
    integer(i8), allocatable :: ids(:)
    integer :: nseg, s, k, n

    call surf%free()
    nseg = size(segments, 2)
    surf%nseg = nseg
    allocate(surf%segments(4, nseg), surf%segment_id(nseg))
    surf%segments = segments
    surf%segment_id = segment_id
    ! Surface nodes in ascending global id (a sort: nothing sized by the
    ! largest node id); local(k, s) is corner k's surface node.
    ids = int(reshape(segments, [4 * nseg]), i8)
    call sort_unique(ids)
    surf%nnode = size(ids)
    surf%nodes = int(ids, ik)
    allocate(local(4, nseg))
    do s = 1, nseg
      do k = 1, 4
        local(k, s) = sorted_find(ids, int(segments(k, s), i8))
      end do
    end do
    ! Node -> segment CSR; segments are visited in order, so each list ascends.
    allocate(surf%node_start(surf%nnode + 1), fill(surf%nnode))
    fill = 0
    do s = 1, nseg
      do k = 1, 4
        fill(local(k, s)) = fill(local(k, s)) + 1
      end do
    end do
    surf%node_start(1) = 1
    do n = 1, surf%nnode
      surf%node_start(n + 1) = surf%node_start(n) + fill(n)
    end do
    allocate(surf%node_segments(surf%node_start(surf%nnode + 1) - 1))
    fill = 0
    do s = 1, nseg
      do k = 1, 4
        n = local(k, s)
        surf%node_segments(surf%node_start(n) + fill(n)) = s
        fill(n) = fill(n) + 1
      end do
    end do
    if (present(adjacent)) then
      if (.not. adjacent) return
    end if
    ! Neighbours: the other segment holding both ends of edge k.
    allocate(surf%neighbours(4, nseg), surf%edge_convex(4, nseg))
    do s = 1, nseg
      do k = 1, 4
        surf%neighbours(k, s) = find_neighbour(s, local(k, s), segments(edge_end(k), s))
      end do
    end do
    if (present(x)) then
      call surface_update_edges(surf, x)
    else
      surf%edge_convex = .true.
    end if

  contains

    integer function find_neighbour(self, na, b) result(t)
      integer, intent(in) :: self, na !< the segment, its edge's first surface node
      integer(ik), intent(in) :: b !< the edge's second node (global id)
      integer :: i
      do i = surf%node_start(na), surf%node_start(na + 1) - 1
        t = surf%node_segments(i)
        if (t /= self .and. any(segments(:, t) == b)) return
      end do
      t = 0
    end function find_neighbour

  end subroutine surface_from_segments


  !> The surface raw (global node ids) with its nodes numbered by their
  !> place in the ascending ids (every node of raw among them); convexity
  !> from x, indexed the same way.
  subroutine surface_renumbered(raw, ids, x, surf)
    type(contact_surface_t), intent(in) :: raw
    integer(i8), intent(in) :: ids(:) !< ascending global node ids
    real(rk), intent(in) :: x(:, :) !< (3, size(ids))
    type(contact_surface_t), intent(inout) :: surf
    integer(ik), allocatable :: segments(:, :)
    integer :: s, c
    allocate(segments(4, raw%nseg))
    do s = 1, raw%nseg
      do c = 1, 4
        segments(c, s) = int(sorted_find(ids, int(raw%segments(c, s), i8)), ik)
      end do
    end do
    call surface_from_segments(segments, raw%segment_id, x, surf)
  end subroutine surface_renumbered

  !> The surface raw (global node ids) moved into surf with its nodes
  !> numbered by their place in the ascending ids (every node of raw among
  !> them): the same surface as surface_renumbered builds (the numbering is
  !> monotone, so the node order, the node -> segment lists and the
  !> neighbours stay as they are), without a second copy and without edge
  !> flags. raw is left empty.
  subroutine surface_relabelled(raw, ids, surf)
    type(contact_surface_t), intent(inout) :: raw
    integer(i8), intent(in) :: ids(:) !< ascending global node ids
    type(contact_surface_t), intent(inout) :: surf
    integer :: s, c, i
    call surf%free()
    do s = 1, raw%nseg
      do c = 1, 4
        raw%segments(c, s) = int(sorted_find(ids, int(raw%segments(c, s), i8)), ik)
      end do
    end do
    do i = 1, raw%nnode
      raw%nodes(i) = int(sorted_find(ids, int(raw%nodes(i), i8)), ik)
    end do
    surf%nseg = raw%nseg
    surf%nnode = raw%nnode
    call move_alloc(raw%segments, surf%segments)
    call move_alloc(raw%segment_id, surf%segment_id)
    call move_alloc(raw%nodes, surf%nodes)
    call move_alloc(raw%node_start, surf%node_start)
    call move_alloc(raw%node_segments, surf%node_segments)
    call move_alloc(raw%neighbours, surf%neighbours)
    call raw%free()
  end subroutine surface_relabelled

  !> Recompute the convex flag of every edge from the current positions.
  subroutine surface_update_edges(surf, x)
    type(contact_surface_t), intent(inout) :: surf
    real(rk), intent(in) :: x(:, :) !< (3, nnode) node positions
    real(rk) :: normal_s(3), normal_t(3), edge(3), turn(3)
    integer :: s, t, k

    do s = 1, surf%nseg
      normal_s = quad_unit_normal(x(:, surf%segments(:, s)))
      do k = 1, 4
        t = surf%neighbours(k, s)
        if (t == 0) then
          surf%edge_convex(k, s) = .true.
          cycle
        end if
        normal_t = quad_unit_normal(x(:, surf%segments(:, t)))
        edge = x(:, surf%segments(edge_end(k), s)) - x(:, surf%segments(k, s))
        turn = [normal_s(2) * normal_t(3) - normal_s(3) * normal_t(2), &
            normal_s(3) * normal_t(1) - normal_s(1) * normal_t(3), &
            normal_s(1) * normal_t(2) - normal_s(2) * normal_t(1)]
        surf%edge_convex(k, s) = dot_product(turn, edge) > CONVEX_TOLERANCE * norm2(edge)
      end do
    end do
  end subroutine surface_update_edges

  !> Index of global node id in surf%nodes (binary search), 0 if absent.
  pure integer function surface_node_index(surf, id) result(i)
    type(contact_surface_t), intent(in) :: surf
    integer, intent(in) :: id !< global node id
    integer :: lo, hi
    lo = 1
    hi = surf%nnode
    do while (lo <= hi)
      i = (lo + hi) / 2
      if (surf%nodes(i) == id) then
        return
      else if (surf%nodes(i) < id) then
        lo = i + 1
      else
        hi = i - 1
      end if
    end do
    i = 0
  end function surface_node_index

  !> The segments given (any order, repeats allowed) and every segment
  !> sharing a node with one of them: ascending, without repeats.
  function ring_of(surf, segs) result(ring)
    type(contact_surface_t), intent(in) :: surf
    integer, intent(in) :: segs(:)
    integer, allocatable :: ring(:)
    integer(i8), allocatable :: grown(:), given(:)
    integer :: j, c, n, e, count, pass
    ! (a pair list names a segment many times)
    allocate(given(size(segs)))
    given(:) = int(segs, i8)
    call sort_unique(given)
    do pass = 1, 2
      count = 0
      do j = 1, size(given)
        do c = 1, 4
          n = surface_node_index(surf, surf%segments(c, given(j)))
          do e = surf%node_start(n), surf%node_start(n + 1) - 1
            count = count + 1
            if (pass == 2) grown(count) = int(surf%node_segments(e), i8)
          end do
        end do
      end do
      if (pass == 1) allocate(grown(count))
    end do
    call sort_unique(grown)
    ring = int(grown)
  end function ring_of

  !> The segments list (ascending) of a whole surface as a local surface:
  !> its nodes numbered by their place in local_set (ascending, holding
  !> them all), the segments in the list's order; edge flags from xloc, the
  !> same as the whole surface's for every segment whose neighbours are all
  !> listed.
  subroutine local_surface(all, list, local_set, xloc, surf)
    type(contact_surface_t), intent(in) :: all
    integer, intent(in) :: list(:)
    integer, intent(in) :: local_set(:)
    real(rk), intent(in) :: xloc(:, :)
    type(contact_surface_t), intent(inout) :: surf
    integer(ik), allocatable :: segments(:, :)
    integer(i8), allocatable :: set(:)
    integer :: j, c
    allocate(segments(4, size(list)))
    set = int(local_set, i8)
    do j = 1, size(list)
      do c = 1, 4
        segments(c, j) = int(sorted_find(set, int(all%segments(c, list(j)), i8)), ik)
      end do
    end do
    call surface_from_segments(segments, all%segment_id(list), xloc, surf)
  end subroutine local_surface

  !> A master segment and every segment sharing a node with it, ascending.
  subroutine master_neighbourhood(surf, s, list, n)
    type(contact_surface_t), intent(in) :: surf
    integer, intent(in) :: s
    integer, intent(out) :: list(:)
    integer, intent(out) :: n
    integer :: c, k, e, t
    n = 0
    do c = 1, 4
      k = surface_node_index(surf, surf%segments(c, s))
      do e = surf%node_start(k), surf%node_start(k + 1) - 1
        t = surf%node_segments(e)
        if (any(list(:n) == t)) cycle
        if (n == size(list)) exit
        n = n + 1
        list(n) = t
      end do
    end do
    call sort_values(list(:n))
  end subroutine master_neighbourhood

  !> DAM self-contact: a node is the slave of a segment only from the side
  !> with the lower segment ids (its lowest segment id below the segment's),
  !> so each pair of facing sides is matched once, as two surfaces would be
  !> (both sides as slaves would exchange everything twice). With
  !> symmetric = .true. the reverse pass keeps the other side (upper): the
  !> nodes of the higher-id side, which the first pass matched only as
  !> masters, are then slaves of the lower-id side's segments.
  subroutine keep_lower_side(surf, pairs, upper)
    type(contact_surface_t), intent(in) :: surf
    integer, allocatable, intent(inout) :: pairs(:, :) !< (2, n) node, segment
    !> keep the other side instead (the reverse pass of symmetric = .true.)
    logical, intent(in) :: upper
    integer(i8) :: lowest
    integer :: m, kept, k
    kept = 0
    do m = 1, size(pairs, 2)
      k = surface_node_index(surf, int(pairs(1, m), ik))
      lowest = minval(surf%segment_id(surf%node_segments(surf%node_start(k): &
          surf%node_start(k + 1) - 1)))
      if ((lowest < surf%segment_id(pairs(2, m))) .eqv. upper) cycle
      kept = kept + 1
      pairs(:, kept) = pairs(:, m)
    end do
    pairs = pairs(:, :kept)
  end subroutine keep_lower_side

  !> Nodal (dual-cell) areas of a surface's nodes, indexed by contact index.
  subroutine nodal_areas(x, surf, area)
    real(rk), intent(in) :: x(:, :)
    type(contact_surface_t), intent(in) :: surf
    real(rk), intent(inout) :: area(:) !< (ncn), zeroed here on the surface nodes
    real(rk) :: corner(4)
    integer :: s, c
    do s = 1, surf%nseg
      area(surf%segments(:, s)) = 0.0_rk
    end do
    do s = 1, surf%nseg
      call corner_areas(x(:, surf%segments(:, s)), corner)
      do c = 1, 4
        area(surf%segments(c, s)) = area(surf%segments(c, s)) + corner(c)
      end do
    end do
  end subroutine nodal_areas

end module contact_surface
