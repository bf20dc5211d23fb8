!> Reader of Exodus II meshes (Cubit/Trelis, SEACAS, meshio, ...) into a
!> global_mesh_t, through the Exodus II C library (Debian libexodusii-dev) and
!> the thin C layer mesh_exodus_c.c.
!>
!> Zones are the elements of the element blocks, which must all be 8-node
!> hexahedra (HEX8, also written HEX or HEXAHEDRON); the element blocks, in
!> file order, are the blocks of the mesh, named by the file's block names
!> ('block_<id>' for a block without a name). Side sets become face sets
!> (named the same way, 'sideset_<id>' without a name); Exodus side s of a
!> hexahedron is the mesh_geometry face EXODUS_SIDE_FACE(s). Node sets are
!> ignored. Nodes used by the hexahedra are renumbered 1..nnode in file
!> order; zones keep the file's element order (the order side sets count in).
!> Exodus's HEX8 node order is the VTK order used by mesh_geometry.
module mesh_exodus
  use, intrinsic :: iso_c_binding, only: c_int, c_double, c_float, c_char, c_null_char
  use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
  use core_kinds, only: rk, ik
  use core_status, only: status_t
  use core_text, only: itoa => to_text
  use mesh_geometry, only: hex_volume
  use mesh_global, only: global_mesh_t, NAME_LEN
  implicit none
  private
  public :: mesh_read_exodus

  !> mesh_geometry face of Exodus side 1..6 (sides 1-4 the faces through edges
  !> 1-2, 2-3, 3-4, 4-1 of the bottom, 5 the bottom 1-4-3-2, 6 the top 5-6-7-8).
  integer, parameter, public :: EXODUS_SIDE_FACE(6) = [3, 4, 5, 6, 1, 2]
  integer, parameter :: KIND_BLOCK = 1, KIND_SIDE_SET = 3
  integer, parameter :: MAX_REPORT = 10
  integer, parameter :: TEXT_LEN = 257

  interface
    integer(c_int) function exo_open(path, exoid, version) bind(C, name='impact3d_exo_open')
      import :: c_int, c_char, c_float
      character(kind=c_char), intent(in) :: path(*)
      integer(c_int), intent(out) :: exoid
      real(c_float), intent(out) :: version
    end function exo_open
    integer(c_int) function exo_close(exoid) bind(C, name='impact3d_exo_close')
      import :: c_int
      integer(c_int), value :: exoid
    end function exo_close
    integer(c_int) function exo_init(exoid, ndim, nnode, nelem, nblock, nnodeset, nsideset) &
        bind(C, name='impact3d_exo_init')
      import :: c_int
      integer(c_int), value :: exoid
      integer(c_int), intent(out) :: ndim, nnode, nelem, nblock, nnodeset, nsideset
    end function exo_init
    integer(c_int) function exo_coord(exoid, x, y, z) bind(C, name='impact3d_exo_coord')
      import :: c_int, c_double
      integer(c_int), value :: exoid
      real(c_double), intent(out) :: x(*), y(*), z(*)
    end function exo_coord
    integer(c_int) function exo_ids(exoid, kind, ids) bind(C, name='impact3d_exo_ids')
      import :: c_int
      integer(c_int), value :: exoid, kind
      integer(c_int), intent(out) :: ids(*)
    end function exo_ids
    integer(c_int) function exo_name(exoid, kind, id, name, length) &
        bind(C, name='impact3d_exo_name')
      import :: c_int, c_char
      integer(c_int), value :: exoid, kind, id, length
      character(kind=c_char), intent(out) :: name(*)
    end function exo_name
    integer(c_int) function exo_block(exoid, id, type, length, nelem, nper) &
        bind(C, name='impact3d_exo_block')
      import :: c_int, c_char
      integer(c_int), value :: exoid, id, length
      character(kind=c_char), intent(out) :: type(*)
      integer(c_int), intent(out) :: nelem, nper
    end function exo_block
    integer(c_int) function exo_conn(exoid, id, conn) bind(C, name='impact3d_exo_conn')
      import :: c_int
      integer(c_int), value :: exoid, id
      integer(c_int), intent(out) :: conn(*)
    end function exo_conn
    integer(c_int) function exo_side_set_size(exoid, id, nside) &
        bind(C, name='impact3d_exo_side_set_size')
      import :: c_int
      integer(c_int), value :: exoid, id
      integer(c_int), intent(out) :: nside
    end function exo_side_set_size
    integer(c_int) function exo_side_set(exoid, id, elem, side) &
        bind(C, name='impact3d_exo_side_set')
      import :: c_int
      integer(c_int), value :: exoid, id
      integer(c_int), intent(out) :: elem(*), side(*)
    end function exo_side_set
  end interface

contains

  !> Read an Exodus II file. Every problem goes to status with a message
  !> starting "mesh file '<path>': "; on any problem the mesh is left empty.
  subroutine mesh_read_exodus(path, mesh, block_names, status)
    character(len=*), intent(in) :: path !< the Exodus II file (full path)
    type(global_mesh_t), intent(inout) :: mesh !< the mesh read; zone_block indexes block_names
    !> Names of the element blocks in file order.
    character(len=NAME_LEN), allocatable, intent(out) :: block_names(:)
    type(status_t), intent(inout) :: status !< problems are added here
    character(len=:), allocatable :: prefix
    logical :: exists
    integer(c_int) :: exoid, ndim, nnode, nelem, nblock, nnodeset, nsideset
    real(c_float) :: version
    integer :: count0

    prefix = "mesh file '"//trim(path)//"': "
    count0 = status%count
    call mesh%free()
    allocate(block_names(0))
    inquire(file=path, exist=exists)
    if (.not. exists) then
      call status%add(prefix//'no such file')
      return
    end if
    if (exo_open(trim(path)//c_null_char, exoid, version) /= 0) then
      call status%add(prefix//'cannot open it as an Exodus II file (the Exodus II library '// &
          'could not read it: not a netCDF file, or damaged)')
      return
    end if
    if (exo_init(exoid, ndim, nnode, nelem, nblock, nnodeset, nsideset) /= 0) then
      call status%add(prefix//'cannot read its sizes (ex_get_init failed)')
    else if (ndim /= 3) then
      call status%add(prefix//'the mesh is '//itoa(int(ndim))//'D; impact3d reads 3D meshes')
    else if (nblock < 1 .or. nelem < 1) then
      call status%add(prefix//'the file has no element block (no elements)')
    else
      call read_mesh(exoid, prefix, int(nnode), int(nelem), int(nblock), int(nsideset), mesh, &
          block_names, status)
    end if
    if (exo_close(exoid) /= 0) call status%add(prefix//'cannot close it (ex_close failed)')
    if (status%count > count0) then
      call mesh%free()
      if (allocated(block_names)) deallocate(block_names)
      allocate(block_names(0))
    end if
  end subroutine mesh_read_exodus

  !> Everything after the sizes: coordinates, blocks, side sets, checks.
  subroutine read_mesh(exoid, prefix, nnode, nelem, nblock, nsideset, mesh, block_names, status)
    integer(c_int), intent(in) :: exoid
    character(len=*), intent(in) :: prefix
    integer, intent(in) :: nnode, nelem, nblock, nsideset
    type(global_mesh_t), intent(inout) :: mesh
    character(len=NAME_LEN), allocatable, intent(inout) :: block_names(:)
    type(status_t), intent(inout) :: status
    real(c_double), allocatable :: xc(:), yc(:), zc(:)
    integer(c_int), allocatable :: ids(:), conn(:), elem(:), side(:)
    integer(c_int) :: n_in_block, nper, nside
    integer, allocatable :: new_id(:), conn_all(:, :), zone_of_block(:)
    character(len=TEXT_LEN) :: type_text
    character(len=NAME_LEN), allocatable :: set_names(:)
    integer :: b, e, k, z, n, nbad, count0, s, nface
    logical :: bad_node

    count0 = status%count
    allocate(xc(nnode), yc(nnode), zc(nnode))
    if (exo_coord(exoid, xc, yc, zc) /= 0) then
      call status%add(prefix//'cannot read the node coordinates (ex_get_coord failed)')
      return
    end if
    nbad = 0
    do n = 1, nnode
      if (.not. (ieee_is_finite(xc(n)) .and. ieee_is_finite(yc(n)) .and. ieee_is_finite(zc(n)))) &
          call status%add_capped(nbad, MAX_REPORT, prefix//'node '//itoa(n)//' has a coordinate that is '// &
          'not a finite number')
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'nodes with non-finite coordinates')

    ! Element blocks: names, types, connectivity.
    if (allocated(block_names)) deallocate(block_names)
    allocate(ids(nblock), block_names(nblock), zone_of_block(nelem), conn_all(8, nelem))
    if (exo_ids(exoid, KIND_BLOCK, ids) /= 0) then
      call status%add(prefix//'cannot read the element block ids (ex_get_ids failed)')
      return
    end if
    call entity_names(exoid, KIND_BLOCK, ids, 'block_', 'element block', prefix, block_names, &
        status)
    e = 0
    bad_node = .false.
    do b = 1, nblock
      if (exo_block(exoid, ids(b), type_text, len(type_text, c_int), n_in_block, nper) /= 0) then
        call status%add(prefix//'cannot read element block '''//trim(block_names(b))// &
            ''' (id '//itoa(int(ids(b)))//'): ex_get_block failed')
        return
      end if
      type_text = c_text(type_text)
      if (.not. is_hex8(type_text, int(nper))) then
        call status%add(prefix//'element block '''//trim(block_names(b))//''' (id '// &
            itoa(int(ids(b)))//') holds '//itoa(int(n_in_block))//' elements of type '''// &
            trim(type_text)//''' with '//itoa(int(nper))//' nodes; impact3d reads 8-node '// &
            'hexahedra (HEX8) only')
        cycle
      end if
      if (e + n_in_block > nelem) then
        call status%add(prefix//'the element blocks hold more elements than the file''s '// &
            'element count '//itoa(nelem))
        return
      end if
      if (n_in_block == 0) cycle
      allocate(conn(8 * n_in_block))
      if (exo_conn(exoid, ids(b), conn) /= 0) then
        call status%add(prefix//'cannot read the connectivity of element block '''// &
            trim(block_names(b))//''' (ex_get_conn failed)')
        return
      end if
      do k = 1, n_in_block
        conn_all(:, e + k) = conn(8 * (k - 1) + 1:8 * k)
        zone_of_block(e + k) = b
        if (any(conn(8 * (k - 1) + 1:8 * k) < 1 .or. conn(8 * (k - 1) + 1:8 * k) > nnode)) &
            bad_node = .true.
      end do
      e = e + n_in_block
      deallocate(conn)
    end do
    if (bad_node) call status%add(prefix//'an element refers to a node outside 1..'//itoa(nnode))
    if (status%count > count0) return
    if (e /= nelem) then
      call status%add(prefix//'the element blocks hold '//itoa(e)//' elements, the file '// &
          'says '//itoa(nelem))
      return
    end if

    ! Nodes used by the hexahedra, in file order.
    allocate(new_id(nnode))
    new_id = 0
    do z = 1, nelem
      new_id(conn_all(:, z)) = 1
    end do
    n = 0
    do k = 1, nnode
      if (new_id(k) == 0) cycle
      n = n + 1
      new_id(k) = n
    end do
    mesh%nnode = n
    mesh%nzone = nelem
    allocate(mesh%coordinates(3, n), mesh%connectivity(8, nelem), mesh%zone_block(nelem))
    do k = 1, nnode
      if (new_id(k) > 0) mesh%coordinates(:, new_id(k)) = [real(xc(k), rk), real(yc(k), rk), &
          real(zc(k), rk)]
    end do
    nbad = 0
    do z = 1, nelem
      mesh%connectivity(:, z) = int(new_id(conn_all(:, z)), ik)
      mesh%zone_block(z) = int(zone_of_block(z), ik)
      if (.not. hex_volume(mesh%coordinates(:, mesh%connectivity(:, z))) > 0.0_rk) &
          call status%add_capped(nbad, MAX_REPORT, prefix//'element '//itoa(z)//' of block '''// &
          trim(block_names(zone_of_block(z)))//''' has a volume <= 0 (nodes not in the '// &
          'Exodus HEX8 order, or a degenerate element)')
    end do
    call status%add_more(prefix, nbad, MAX_REPORT, 'elements with a volume <= 0')

    ! Side sets.
    allocate(mesh%set_start(nsideset + 1))
    mesh%set_start(1) = 1
    allocate(mesh%set_zone(0), mesh%set_face(0))
    allocate(set_names(nsideset))
    mesh%nset = nsideset
    if (nsideset > 0) then
      deallocate(ids)
      allocate(ids(nsideset))
      if (exo_ids(exoid, KIND_SIDE_SET, ids) /= 0) then
        call status%add(prefix//'cannot read the side set ids (ex_get_ids failed)')
        return
      end if
      call entity_names(exoid, KIND_SIDE_SET, ids, 'sideset_', 'side set', prefix, set_names, &
          status)
    end if
    do s = 1, nsideset
      if (exo_side_set_size(exoid, ids(s), nside) /= 0) then
        call status%add(prefix//'cannot read side set '''//trim(set_names(s))// &
            ''' (ex_get_set_param failed)')
        return
      end if
      allocate(elem(max(nside, 1)), side(max(nside, 1)))
      if (nside > 0) then
        if (exo_side_set(exoid, ids(s), elem, side) /= 0) then
          call status%add(prefix//'cannot read side set '''//trim(set_names(s))// &
              ''' (ex_get_set failed)')
          return
        end if
      end if
      nface = mesh%set_start(s) - 1
      mesh%set_zone = [mesh%set_zone, int(elem(:nside), ik)]
      mesh%set_face = [mesh%set_face, int(side(:nside), ik)]
      nbad = 0
      do k = nface + 1, nface + nside
        if (mesh%set_zone(k) < 1 .or. mesh%set_zone(k) > nelem .or. mesh%set_face(k) < 1 .or. &
            mesh%set_face(k) > 6) then
          call status%add_capped(nbad, MAX_REPORT, prefix//'side set '''//trim(set_names(s))//''': entry '// &
              itoa(k - nface)//' names element '//itoa(int(mesh%set_zone(k)))//', side '// &
              itoa(int(mesh%set_face(k)))//' (elements are 1..'//itoa(nelem)// &
              ', sides of a HEX8 1..6)')
        else
          mesh%set_face(k) = int(EXODUS_SIDE_FACE(mesh%set_face(k)), ik)
        end if
      end do
      call status%add_more(prefix, nbad, MAX_REPORT, 'bad entries of side set '''// &
          trim(set_names(s))//'''')
      mesh%set_start(s + 1) = nface + nside + 1
      deallocate(elem, side)
    end do
    call move_alloc(set_names, mesh%set_name)
  end subroutine read_mesh

  !> Names of the blocks or sets ids: the file's, else default_prefix<id>;
  !> each at most NAME_LEN characters and different from the others.
  subroutine entity_names(exoid, kind, ids, default_prefix, what, prefix, names, status)
    integer(c_int), intent(in) :: exoid, kind, ids(:)
    character(len=*), intent(in) :: default_prefix, what, prefix
    character(len=NAME_LEN), intent(out) :: names(:)
    type(status_t), intent(inout) :: status
    character(len=TEXT_LEN) :: text
    integer :: i, j
    do i = 1, size(ids)
      text = ''
      if (exo_name(exoid, kind, ids(i), text, len(text, c_int)) /= 0) text = ''
      text = c_text(text)
      if (len_trim(text) == 0) text = default_prefix//itoa(int(ids(i)))
      if (len_trim(text) > NAME_LEN) call status%add(prefix//'the name '''//trim(text)// &
          ''' of '//what//' '//itoa(int(ids(i)))//' is longer than '//itoa(NAME_LEN)// &
          ' characters')
      if (scan(trim(text), ' ,') > 0) call status%add(prefix//'the name '''//trim(text)// &
          ''' of '//what//' '//itoa(int(ids(i)))//' contains a blank or a comma (deck lists '// &
          'of names are separated by them); rename it in the meshing tool')
      names(i) = text(1:NAME_LEN)
      do j = 1, i - 1
        if (names(j) == names(i)) call status%add(prefix//what//'s '//itoa(int(ids(j)))// &
            ' and '//itoa(int(ids(i)))//' have the same name '''//trim(names(i))//'''')
      end do
    end do
  end subroutine entity_names

  !> An 8-node hexahedron by its Exodus type name.
  logical function is_hex8(type_text, nper)
    character(len=*), intent(in) :: type_text
    integer, intent(in) :: nper
    character(len=len(type_text)) :: upper
    integer :: i, c
    upper = type_text
    do i = 1, len(upper)
      c = iachar(upper(i:i))
      if (c >= iachar('a') .and. c <= iachar('z')) upper(i:i) = achar(c - 32)
    end do
    is_hex8 = nper == 8 .and. (trim(upper) == 'HEX8' .or. trim(upper) == 'HEX' .or. &
        trim(upper) == 'HEXAHEDRON')
  end function is_hex8

  !> A C string (up to its NUL) as blank-padded Fortran text.
  pure function c_text(text) result(clean)
    character(len=*), intent(in) :: text
    character(len=len(text)) :: clean
    integer :: k
    k = index(text, c_null_char)
    clean = text
    if (k > 0) clean = text(1:k - 1)
  end function c_text

end module mesh_exodus
