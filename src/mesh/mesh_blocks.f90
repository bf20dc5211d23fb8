!> Parts made of structured blocks of hexes (the curved generators of
!> mesh_curved), built without holding the part: a block's node positions
!> come from a point function, so a rank makes only the zones of its range.
!>
!> A part is a list of blocks of n(1) x n(2) x n(3) hexes. Raw point
!> (b, i, j, k), i = 0..n(1) fastest, has the raw id node_offset(b) + 1 + i +
!> (n(1) + 1) (j + (n(2) + 1) k). A block whose first hex comes out
!> left-handed is mirrored in i (its point (i, j, k) is the raw point
!> (n(1) - i, j, k), and its i faces swap sets), so every hex has the
!> positive (VTK) node order. Zones are numbered block by block, i fastest.
!>
!> Numbering. Raw points that blocks share lie on block faces; they are
!> merged by position (within MERGE_TOLERANCE of the part's size). Only the
!> face points of the blocks are merged (the part's surface, not its volume):
!> they are sorted by the key DIRECTION . x (stable, so ties keep raw order),
!> and each point not yet merged takes the later points of its key window
!> within the tolerance. A group's node id is its place among the groups in
!> order of their lowest raw id (order of first appearance), and its
!> position is that of the group's first point in key order. A rank needs
!> only the duplicates' raw ids to number any node: id = first - (number of
!> duplicates below first). This is the numbering the whole-part assembly
!> had, bit for bit.
!>
!> Face sets. Block face f (mesh_geometry order: k-, k+, j-, i+, j+, i-) of
!> set s > 0 adds its faces; a set lists, block by block and face by face in
!> that order, the faces of each block face with k slowest and i fastest.
module mesh_blocks
  use core_kinds, only: rk, ik, i8
  use core_sort, only: sort_order, sorted_find
  use mesh_geometry, only: hex_volume
  use mesh_global, only: global_mesh_t, NAME_LEN
  use mesh_range, only: mesh_range_t, range_grow_faces
  implicit none
  private
  public :: part_prepare, part_assemble, range_add_part, part_set_counts

  !> Nodes closer than this fraction of the part's size are one node.
  real(rk), parameter :: MERGE_TOLERANCE = 1.0e-10_rk
  !> A direction along no mesh line, so few points share a key.
  real(rk), parameter :: DIRECTION(3) = [0.8017_rk, 0.5323_rk, 0.2719_rk]

  !> A part of structured blocks; raw_point gives a block's node positions.
  type, abstract, public :: block_part_t
    integer :: nblock = 0
    integer, allocatable :: n(:, :) !< (3, nblock) zones in i, j, k
    integer, allocatable :: face_set(:, :) !< (6, nblock) set of each block face, 0: none
    character(len=NAME_LEN), allocatable :: set_names(:) !< indexed by face_set
    real(rk) :: length_scale = 1.0_rk !< the part's size, for the merge tolerance
    ! Filled by part_prepare:
    logical, allocatable :: mirrored(:) !< (nblock) block mirrored in i
    integer(i8), allocatable :: node_offset(:), zone_offset(:) !< (nblock) raw points, zones before
    integer(i8) :: nraw = 0, nzone = 0, nnode = 0
    integer(i8), allocatable :: dup(:) !< raw ids merged into an earlier point, ascending
    integer(i8), allocatable :: dup_first(:) !< the lowest raw id of each one's group
    integer(i8), allocatable :: lead(:) !< lowest raw ids of groups whose position is another's
    integer(i8), allocatable :: lead_from(:) !< the raw id whose position each such group has
  contains
    procedure(raw_point_i), deferred :: raw_point
    procedure :: point => part_point
  end type block_part_t

  abstract interface
    !> Position of point (i, j, k) of block b as generated (before mirroring).
    pure function raw_point_i(this, b, i, j, k) result(x)
      import :: block_part_t, rk
      class(block_part_t), intent(in) :: this
      integer, intent(in) :: b, i, j, k
      real(rk) :: x(3)
    end function raw_point_i
  end interface

contains

  !> Position of point (i, j, k) of block b in the oriented block.
  pure function part_point(this, b, i, j, k) result(x)
    class(block_part_t), intent(in) :: this
    integer, intent(in) :: b, i, j, k
    real(rk) :: x(3)
    if (this%mirrored(b)) then
      x = this%raw_point(b, this%n(1, b) - i, j, k)
    else
      x = this%raw_point(b, i, j, k)
    end if
  end function part_point

  !> Orient the blocks, count zones and raw points, and merge the points of
  !> the block faces (the numbering of the module header). Every rank does
  !> the same; the work and memory are those of the part's block faces.
  subroutine part_prepare(part)
    class(block_part_t), intent(inout) :: part
    integer(i8), allocatable :: raw(:), group(:), lowest(:)
    real(rk), allocatable :: x(:, :), key(:)
    integer, allocatable :: order(:), rep(:)
    real(rk) :: corners(3, 8), window, tolerance
    integer :: b, swap, m, a, c, p, q, npoint, ndup, nlead

    allocate(part%mirrored(part%nblock), part%node_offset(part%nblock), &
        part%zone_offset(part%nblock))
    part%mirrored = .false.
    part%nraw = 0
    part%nzone = 0
    do b = 1, part%nblock
      corners = hex_corners(part, b, 0, 0, 0)
      if (hex_volume(corners) < 0.0_rk) then
        part%mirrored(b) = .true.
        swap = part%face_set(4, b)
        part%face_set(4, b) = part%face_set(6, b)
        part%face_set(6, b) = swap
      end if
      part%node_offset(b) = part%nraw
      part%zone_offset(b) = part%nzone
      part%nraw = part%nraw + product(int(part%n(:, b) + 1, i8))
      part%nzone = part%nzone + product(int(part%n(:, b), i8))
    end do

    ! The block faces' raw points, ascending, and their positions.
    call face_points(part, raw)
    npoint = size(raw)
    allocate(x(3, npoint))
    do m = 1, npoint
      x(:, m) = raw_position(part, raw(m))
    end do
    key = matmul(DIRECTION, x)
    call sort_order(key, order)
    tolerance = MERGE_TOLERANCE * part%length_scale
    window = tolerance * norm2(DIRECTION)
    allocate(rep(npoint))
    rep = 0
    do a = 1, npoint
      p = order(a)
      if (rep(p) /= 0) cycle
      rep(p) = p
      do c = a + 1, npoint
        q = order(c)
        if (key(q) - key(p) > window) exit
        if (rep(q) == 0) then
          if (norm2(x(:, q) - x(:, p)) <= tolerance) rep(q) = p
        end if
      end do
    end do
    ! Each group's lowest raw id (raw ascends, so the first member met).
    allocate(lowest(npoint))
    lowest = 0
    do m = 1, npoint
      if (lowest(rep(m)) == 0) lowest(rep(m)) = raw(m)
    end do
    allocate(group(npoint))
    do m = 1, npoint
      group(m) = lowest(rep(m))
    end do
    ndup = count(group /= raw)
    part%dup = pack(raw, group /= raw)
    part%dup_first = pack(group, group /= raw)
    ! Groups whose position point (the first in key order) is not the lowest.
    nlead = 0
    do m = 1, npoint
      if (rep(m) == m .and. lowest(m) /= raw(m)) nlead = nlead + 1
    end do
    allocate(part%lead(nlead), part%lead_from(nlead))
    nlead = 0
    do m = 1, npoint
      if (rep(m) == m .and. lowest(m) /= raw(m)) then
        nlead = nlead + 1
        part%lead(nlead) = lowest(m)
        part%lead_from(nlead) = raw(m)
      end if
    end do
    call sort_order(part%lead, order)
    part%lead = part%lead(order)
    part%lead_from = part%lead_from(order)
    part%nnode = part%nraw - ndup
  end subroutine part_prepare

  !> The raw ids of every point on a block face, ascending, each once.
  subroutine face_points(part, raw)
    class(block_part_t), intent(in) :: part
    integer(i8), allocatable, intent(out) :: raw(:)
    integer :: b, i, j, k, n(3), pass
    integer(i8) :: count
    do pass = 1, 2
      count = 0
      do b = 1, part%nblock
        n = part%n(:, b)
        do k = 0, n(3)
          do j = 0, n(2)
            do i = 0, n(1)
              if (i /= 0 .and. i /= n(1) .and. j /= 0 .and. j /= n(2) .and. k /= 0 .and. &
                  k /= n(3)) cycle
              count = count + 1
              if (pass == 2) raw(count) = raw_id(part, b, i, j, k)
            end do
          end do
        end do
      end do
      if (pass == 1) allocate(raw(count))
    end do
  end subroutine face_points

  !> Raw id of point (i, j, k) of block b.
  pure integer(i8) function raw_id(part, b, i, j, k)
    class(block_part_t), intent(in) :: part
    integer, intent(in) :: b, i, j, k
    raw_id = part%node_offset(b) + 1_i8 + i + int(part%n(1, b) + 1, i8) * (j + &
        int(part%n(2, b) + 1, i8) * k)
  end function raw_id

  !> Position of the raw point with id r (oriented block).
  pure function raw_position(part, r) result(x)
    class(block_part_t), intent(in) :: part
    integer(i8), intent(in) :: r
    real(rk) :: x(3)
    integer :: b, i, j, k
    call locate(part%node_offset, part%n + 1, r, b, i, j, k)
    x = part%point(b, i, j, k)
  end function raw_position

  !> Block b and place (i, j, k), i fastest, of item id (1-based) of blocks
  !> of dims(:, b) items each, offsets(b) items before block b.
  pure subroutine locate(offsets, dims, id, b, i, j, k)
    integer(i8), intent(in) :: offsets(:), id
    integer, intent(in) :: dims(:, :) !< (3, nblock)
    integer, intent(out) :: b, i, j, k
    integer(i8) :: l
    b = 1
    do while (b < size(offsets))
      if (offsets(b + 1) >= id) exit
      b = b + 1
    end do
    l = id - offsets(b) - 1
    i = int(mod(l, int(dims(1, b), i8)))
    j = int(mod(l / dims(1, b), int(dims(2, b), i8)))
    k = int(l / (int(dims(1, b), i8) * dims(2, b)))
  end subroutine locate

  !> Node id (1-based in the part) of raw point r, and the raw point whose
  !> position the node has.
  pure subroutine node_of(part, r, id, from)
    class(block_part_t), intent(in) :: part
    integer(i8), intent(in) :: r
    integer(i8), intent(out) :: id, from
    integer(i8) :: first
    integer :: m
    first = r
    m = sorted_find(part%dup, r)
    if (m > 0) first = part%dup_first(m)
    id = first - below(part%dup, first)
    from = first
    m = sorted_find(part%lead, first)
    if (m > 0) from = part%lead_from(m)
  end subroutine node_of

  !> Corners (VTK order) of hex (i, j, k) of block b.
  pure function hex_corners(part, b, i, j, k) result(x)
    class(block_part_t), intent(in) :: part
    integer, intent(in) :: b, i, j, k
    real(rk) :: x(3, 8)
    x(:, 1) = part%point(b, i, j, k)
    x(:, 2) = part%point(b, i + 1, j, k)
    x(:, 3) = part%point(b, i + 1, j + 1, k)
    x(:, 4) = part%point(b, i, j + 1, k)
    x(:, 5) = part%point(b, i, j, k + 1)
    x(:, 6) = part%point(b, i + 1, j, k + 1)
    x(:, 7) = part%point(b, i + 1, j + 1, k + 1)
    x(:, 8) = part%point(b, i, j + 1, k + 1)
  end function hex_corners

  !> Raw ids of the corners (VTK order) of hex (i, j, k) of block b.
  pure function hex_raw(part, b, i, j, k) result(r)
    class(block_part_t), intent(in) :: part
    integer, intent(in) :: b, i, j, k
    integer(i8) :: r(8)
    r = [raw_id(part, b, i, j, k), raw_id(part, b, i + 1, j, k), &
        raw_id(part, b, i + 1, j + 1, k), raw_id(part, b, i, j + 1, k), &
        raw_id(part, b, i, j, k + 1), raw_id(part, b, i + 1, j, k + 1), &
        raw_id(part, b, i + 1, j + 1, k + 1), raw_id(part, b, i, j + 1, k + 1)]
  end function hex_raw

  !> Block and (i, j, k) of the part's zone z (1-based).
  pure subroutine zone_of(part, z, b, i, j, k)
    class(block_part_t), intent(in) :: part
    integer(i8), intent(in) :: z
    integer, intent(out) :: b, i, j, k
    call locate(part%zone_offset, part%n, z, b, i, j, k)
  end subroutine zone_of

  !> Faces of each of the part's sets.
  function part_set_counts(part) result(counts)
    class(block_part_t), intent(in) :: part
    integer(i8) :: counts(size(part%set_names))
    integer :: b, f
    counts = 0
    do b = 1, part%nblock
      do f = 1, 6
        if (part%face_set(f, b) > 0) counts(part%face_set(f, b)) = &
            counts(part%face_set(f, b)) + face_size(part%n(:, b), f)
      end do
    end do
  end function part_set_counts

  !> Faces on block face f of a block of n zones.
  pure integer(i8) function face_size(n, f)
    integer, intent(in) :: n(3), f
    select case (f)
    case (1, 2)
      face_size = int(n(1), i8) * n(2)
    case (3, 5)
      face_size = int(n(1), i8) * n(3)
    case default
      face_size = int(n(2), i8) * n(3)
    end select
  end function face_size

  !> Whether hex (i, j, k) of a block of n zones has face f on block face f,
  !> and its 1-based place among that block face's faces (k slowest).
  pure subroutine face_place(n, f, i, j, k, on, place)
    integer, intent(in) :: n(3), f, i, j, k
    logical, intent(out) :: on
    integer(i8), intent(out) :: place
    select case (f)
    case (1)
      on = k == 0
      place = 1 + i + int(n(1), i8) * j
    case (2)
      on = k == n(3) - 1
      place = 1 + i + int(n(1), i8) * j
    case (3)
      on = j == 0
      place = 1 + i + int(n(1), i8) * k
    case (5)
      on = j == n(2) - 1
      place = 1 + i + int(n(1), i8) * k
    case (4)
      on = i == n(1) - 1
      place = 1 + j + int(n(2), i8) * k
    case default
      on = i == 0
      place = 1 + j + int(n(2), i8) * k
    end select
  end subroutine face_place

  !> Faces of set s before block face f of block b in the set's list.
  pure integer(i8) function set_base(part, s, b, f)
    class(block_part_t), intent(in) :: part
    integer, intent(in) :: s, b, f
    integer :: c, g
    set_base = 0
    do c = 1, b
      do g = 1, 6
        if (c == b .and. g >= f) exit
        if (part%face_set(g, c) == s) set_base = set_base + face_size(part%n(:, c), g)
      end do
    end do
  end function set_base

  !> The whole part as a global mesh (nodes in the part's numbering, sets in
  !> their order); zone_block is 0. For tests and small tools: a run builds
  !> only its range (range_add_part).
  subroutine part_assemble(part, mesh)
    class(block_part_t), intent(in) :: part
    type(global_mesh_t), intent(inout) :: mesh
    integer(i8) :: z, id, from, r(8), place, counts(size(part%set_names))
    integer :: b, i, j, k, c, f, s
    logical :: on
    integer(i8), allocatable :: next(:)
    call mesh%free()
    mesh%nzone = int(part%nzone)
    mesh%nnode = int(part%nnode)
    allocate(mesh%coordinates(3, mesh%nnode), mesh%connectivity(8, mesh%nzone), &
        mesh%zone_block(mesh%nzone))
    mesh%zone_block = 0
    do z = 1, part%nzone
      call zone_of(part, z, b, i, j, k)
      r = hex_raw(part, b, i, j, k)
      do c = 1, 8
        call node_of(part, r(c), id, from)
        mesh%connectivity(c, z) = int(id, ik)
        mesh%coordinates(:, id) = raw_position(part, from)
      end do
    end do
    mesh%nset = size(part%set_names)
    allocate(mesh%set_name(mesh%nset), mesh%set_start(mesh%nset + 1))
    mesh%set_name = part%set_names
    counts = part_set_counts(part)
    mesh%set_start(1) = 1
    do s = 1, mesh%nset
      mesh%set_start(s + 1) = mesh%set_start(s) + int(counts(s))
    end do
    allocate(mesh%set_zone(mesh%set_start(mesh%nset + 1) - 1), &
        mesh%set_face(mesh%set_start(mesh%nset + 1) - 1))
    allocate(next(mesh%nset))
    do z = 1, part%nzone
      call zone_of(part, z, b, i, j, k)
      do f = 1, 6
        s = part%face_set(f, b)
        if (s == 0) cycle
        call face_place(part%n(:, b), f, i, j, k, on, place)
        if (.not. on) cycle
        place = mesh%set_start(s) + set_base(part, s, b, f) + place - 1
        mesh%set_zone(place) = int(z, ik)
        mesh%set_face(place) = int(f, ik)
      end do
    end do
  end subroutine part_assemble

  !> The zones of the part (zones zone0 + 1 .., nodes node0 + 1 ..) in this
  !> rank's range: global node ids, corner positions and set faces (sets(m,
  !> s): the range's set m = 1, 2 of the part's set s, 0 for none; ord0: the
  !> faces of that range set before this part). lo..hi: the range's zones
  !> of this part (none when hi < lo). zone_block is left 0.
  subroutine range_add_part(range, part, zone0, node0, sets, ord0, lo, hi)
    type(mesh_range_t), intent(inout) :: range
    class(block_part_t), intent(in) :: part
    integer(i8), intent(in) :: zone0, node0
    integer, intent(in) :: sets(:, :) !< (2, nset of the part)
    integer(i8), intent(in) :: ord0(:, :) !< (2, nset of the part)
    integer, intent(out) :: lo, hi
    integer(i8) :: zfirst, zlast, g, z, id, from, r(8), place
    integer :: local, b, i, j, k, c, f, s, m, pos, nnew, pass
    logical :: on
    zfirst = max(zone0 + 1, range%first)
    zlast = min(zone0 + part%nzone, range%first + range%nzone - 1)
    lo = int(zfirst - range%first) + 1
    hi = int(zlast - range%first) + 1
    if (zlast < zfirst) return
    do g = zfirst, zlast
      local = int(g - range%first) + 1
      z = g - zone0
      call zone_of(part, z, b, i, j, k)
      r = hex_raw(part, b, i, j, k)
      do c = 1, 8
        call node_of(part, r(c), id, from)
        range%conn(c, local) = node0 + id
        range%corner_x(:, c, local) = raw_position(part, from)
      end do
      range%zone_block(local) = 0
    end do
    do pass = 1, 2
      nnew = 0
      pos = range%nface
      do g = zfirst, zlast
        z = g - zone0
        call zone_of(part, z, b, i, j, k)
        do f = 1, 6
          s = part%face_set(f, b)
          if (s == 0) cycle
          call face_place(part%n(:, b), f, i, j, k, on, place)
          if (.not. on) cycle
          do m = 1, 2
            if (sets(m, s) == 0) cycle
            nnew = nnew + 1
            if (pass == 1) cycle
            pos = pos + 1
            range%face_set(pos) = sets(m, s)
            range%face_zone(pos) = int(g - range%first) + 1
            range%face_face(pos) = f
            range%face_ord(pos) = ord0(m, s) + set_base(part, s, b, f) + place
          end do
        end do
      end do
      if (pass == 1) call range_grow_faces(range, nnew)
    end do
    range%nface = pos
  end subroutine range_add_part


  !> How many of the ascending keys are below key.
  pure integer(i8) function below(keys, key)
    integer(i8), intent(in) :: keys(:), key
    integer :: low, high, mid
    low = 0
    high = size(keys)
    ! invariant: keys(1:low) < key, keys(high+1:) >= key
    do while (low < high)
      mid = (low + high + 1) / 2
      if (keys(mid) < key) then
        low = mid
      else
        high = mid - 1
      end if
    end do
    below = low
  end function below

end module mesh_blocks
